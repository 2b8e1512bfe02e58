//! Blockiness: how much of an image's oriented gradient energy lies along the image axes,
//! against the same share in the exemplar.
//!
//! Per pixel the structure tensor of the luminance (Scharr gradients, averaged over a 3×3
//! binomial window) gives a dominant gradient orientation θ and an anisotropic energy
//! λ₁ − λ₂ (zero where the gradients have no preferred direction, as at a block's corner or in
//! noise). The **axis share** is the energy-weighted fraction of pixels whose θ lies within
//! ±π/16 of an image axis: an isotropic texture has 0.25, an image made of axis-aligned blocks
//! close to 1, bricks in between. [`Blockiness::ratio`] divides a result's share by its
//! exemplar's: 1 when the result is as axis-aligned as the material, above when synthesis has
//! added steps along the axes. A blur, a shift or a rotation by 90° leave it near 1, which is
//! what the sliced Wasserstein distance is for.

use super::image::LinearImage;

/// Half-width of the orientation band counted as axis-aligned, in radians of θ.
pub const AXIS_BAND: f64 = std::f64::consts::PI / 16.0;

/// The energy-weighted share of oriented gradient energy within [`AXIS_BAND`] of the axes.
pub fn axis_share(image: &LinearImage) -> f64 {
    let (w, h) = (image.width, image.height);
    if w < 5 || h < 5 {
        return 0.0;
    }
    let y = image.luminance();
    let at = |x: usize, yy: usize| f64::from(y[yy * w + x]);
    // Scharr gradients inside a one-pixel border.
    let mut tensor = vec![[0.0f64; 3]; w * h];
    for yy in 1..h - 1 {
        for x in 1..w - 1 {
            let gx = 3.0 * (at(x + 1, yy - 1) - at(x - 1, yy - 1))
                + 10.0 * (at(x + 1, yy) - at(x - 1, yy))
                + 3.0 * (at(x + 1, yy + 1) - at(x - 1, yy + 1));
            let gy = 3.0 * (at(x - 1, yy + 1) - at(x - 1, yy - 1))
                + 10.0 * (at(x, yy + 1) - at(x, yy - 1))
                + 3.0 * (at(x + 1, yy + 1) - at(x + 1, yy - 1));
            tensor[yy * w + x] = [gx * gx, gy * gy, gx * gy];
        }
    }
    const WEIGHTS: [f64; 3] = [0.25, 0.5, 0.25];
    let (mut axis, mut total) = (0.0f64, 0.0f64);
    for yy in 2..h - 2 {
        for x in 2..w - 2 {
            let mut j = [0.0f64; 3];
            for (dy, wy) in WEIGHTS.iter().enumerate() {
                for (dx, wx) in WEIGHTS.iter().enumerate() {
                    let t = tensor[(yy + dy - 1) * w + x + dx - 1];
                    (0..3).for_each(|k| j[k] += wx * wy * t[k]);
                }
            }
            let (dxx, dxy) = (j[0] - j[1], 2.0 * j[2]);
            let energy = dxx.hypot(dxy);
            if energy <= 0.0 {
                continue;
            }
            // θ = atan2(dxy, dxx) / 2; distance of θ to the nearest axis (multiple of π/2).
            let theta = 0.5 * dxy.atan2(dxx);
            let quarter = std::f64::consts::FRAC_PI_2;
            let off = theta - quarter * (theta / quarter).round();
            total += energy;
            if off.abs() <= AXIS_BAND {
                axis += energy;
            }
        }
    }
    if total > 0.0 {
        axis / total
    } else {
        0.0
    }
}

/// A result's axis share beside its exemplar's.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Blockiness {
    /// The result's axis share.
    pub share: f64,
    /// The exemplar's axis share.
    pub exemplar_share: f64,
    /// `share / exemplar_share`: 1 as axis-aligned as the material.
    pub ratio: f64,
}

impl Blockiness {
    /// Measures `image` against `exemplar`.
    pub fn measure(image: &LinearImage, exemplar: &LinearImage) -> Blockiness {
        Blockiness::against(image, axis_share(exemplar))
    }

    /// Measures `image` against an exemplar share computed once.
    pub fn against(image: &LinearImage, exemplar_share: f64) -> Blockiness {
        let share = axis_share(image);
        Blockiness {
            share,
            exemplar_share,
            ratio: share / exemplar_share.max(1e-9),
        }
    }
}
