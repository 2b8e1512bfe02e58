//! Axis anisotropy: how much more of an image's gradient energy runs along v than along u,
//! and why a volume cannot give all three of its slice families the anisotropy of one
//! exemplar.
//!
//! For an image, `J_uu` and `J_vv` are the sums of the squared central differences of the
//! luminance along u and v over the interior pixels, and the **anisotropy** is
//! `(J_uu − J_vv) / (J_uu + J_vv)`: 0 for an isotropic texture (or one whose structures run
//! along the diagonals), −1 for stripes that run along u (all change is along v), +1 for
//! stripes along v. It is a second moment of the 3×3 patches, so two images with the same
//! patch distribution have the same anisotropy.
//!
//! For a volume, every slice family adds up the same three sums `M_xx`, `M_yy`, `M_zz` (the
//! squared differences along each world axis), each seen by two families
//! ([`ROLE_AXES`](crate::solid::ROLE_AXES): the slices ⊥ x have u = y, v = z; ⊥ y have u = x, v = z; ⊥ z have
//! u = x, v = y). Their differences therefore obey, in **every** volume,
//!
//! ```text
//!     D_x − D_y + D_z = (M_yy − M_zz) − (M_xx − M_zz) + (M_xx − M_yy) = 0,   D = J_uu − J_vv.
//! ```
//!
//! With the three families as energetic as the exemplar (which matching patch distributions
//! asks), an exemplar of anisotropy `a ≠ 0` would need `a − a + a = 0`: at most two families
//! can match it, and when two do the third has anisotropy 0. The closest any volume comes is
//! every family `|a| / 3` away (`a − e, a + e, a − e` with `e = a/3`). Rotating one role's
//! exemplar by 90° flips its sign and only moves the excess (`−a − a + a` or `a + a + a`).
//! This is the "third axis" of anisotropic exemplars (creases, veins or joints running mostly
//! along one image axis): a bound on every solid synthesizer that uses one image for all three
//! roles, measured by [`VolumeAnisotropy`] (`docs/solid.md`).

use super::gradient_moments::{family_moments, moments};
use super::image::LinearImage;
use crate::solid::ROLES;

fn ratio([uu, vv]: [f64; 2]) -> f64 {
    if uu + vv > 0.0 {
        (uu - vv) / (uu + vv)
    } else {
        0.0
    }
}

/// The anisotropy `(J_uu − J_vv) / (J_uu + J_vv)` of an image (module doc); 0 for a flat one.
pub fn anisotropy(image: &LinearImage) -> f64 {
    let [uu, vv, _] = moments(&image.luminance(), image.width, image.height);
    ratio([uu, vv])
}

/// The anisotropy of each slice family of a volume, from every slice's own figure.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct VolumeAnisotropy {
    /// `(J_uu − J_vv) / (J_uu + J_vv)` summed over the slices ⊥ x, ⊥ y, ⊥ z, each in its
    /// role's image axes.
    pub axes: [f64; ROLES],
    /// `D_x − D_y + D_z` over the mean of the three families' `J_uu + J_vv`: zero up to
    /// rounding for every volume (module doc); kept so a report can show it.
    pub residual: f64,
}

impl VolumeAnisotropy {
    /// Measures an RGB cube of side `n`, x fastest. Each family sums its slices' energies
    /// over the slices with a neighbour on both sides along the normal, so that the three
    /// families cover the same interior voxels.
    ///
    /// # Panics
    /// When `colours` does not hold `n³` voxels (a caller's bug).
    pub fn measure(colours: &[[u8; 3]], n: usize) -> VolumeAnisotropy {
        let sums = family_moments(colours, n).map(|[uu, vv, _]| [uu, vv]);
        let d = sums.map(|[uu, vv]| uu - vv);
        let trace = sums.iter().map(|[uu, vv]| uu + vv).sum::<f64>() / ROLES as f64;
        VolumeAnisotropy {
            axes: sums.map(ratio),
            residual: if trace > 0.0 {
                (d[0] - d[1] + d[2]) / trace
            } else {
                0.0
            },
        }
    }
}

/// How far the closest volume can come to exemplars of anisotropy `a` on all three axes:
/// the smallest possible largest `|A_axis − a_axis|`, from `A_x − A_y + A_z = 0` with equal
/// energies (module doc): `|a_x − a_y + a_z| / 3`.
pub fn reachable_gap(a: [f64; ROLES]) -> f64 {
    (a[0] - a[1] + a[2]).abs() / 3.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stripes(n: usize, along_u: bool) -> LinearImage {
        let rgb: Vec<[u8; 3]> = (0..n * n)
            .map(|k| {
                let (x, y) = (k % n, k / n);
                let t = if along_u { y } else { x };
                [(t * 37 % 256) as u8; 3]
            })
            .collect();
        LinearImage::from_rgb8(&rgb, n, n)
    }

    #[test]
    fn stripes_and_noise_rank_as_their_directions() {
        assert!((anisotropy(&stripes(32, true)) + 1.0).abs() < 1e-12);
        assert!((anisotropy(&stripes(32, false)) - 1.0).abs() < 1e-12);
        let mut s = 0x9e37_79b9u32;
        let noise: Vec<[u8; 3]> = (0..64 * 64)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 17;
                s ^= s << 5;
                [(s >> 24) as u8; 3]
            })
            .collect();
        assert!(anisotropy(&LinearImage::from_rgb8(&noise, 64, 64)).abs() < 0.05);
    }

    #[test]
    fn every_volume_obeys_the_identity_and_layers_leave_one_axis_isotropic() {
        let n = 24;
        let mut s = 12345u32;
        let random: Vec<[u8; 3]> = (0..n * n * n)
            .map(|_| {
                s = s.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                [(s >> 24) as u8, (s >> 16) as u8, (s >> 8) as u8]
            })
            .collect();
        let v = VolumeAnisotropy::measure(&random, n);
        assert!(v.residual.abs() < 1e-9, "{v:?}");
        // Layers along z: both families that see z show change along v only (−1); the
        // slices ⊥ z are flat (0): −1 − (−1) + 0 = 0.
        let layers: Vec<[u8; 3]> = (0..n * n * n)
            .map(|k| [((k / (n * n)) * 41 % 256) as u8; 3])
            .collect();
        let v = VolumeAnisotropy::measure(&layers, n);
        assert!((v.axes[0] + 1.0).abs() < 1e-12 && (v.axes[1] + 1.0).abs() < 1e-12);
        assert_eq!(v.axes[2], 0.0);
        assert!(v.residual.abs() < 1e-12);
        assert!((reachable_gap([-0.3; 3]) - 0.1).abs() < 1e-12);
        assert_eq!(reachable_gap([0.0; 3]), 0.0);
    }
}
