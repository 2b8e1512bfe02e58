//! Diagonal orientation: which diagonal an image's structures prefer, and why a volume cannot
//! give all three of its slice families a negative preference.
//!
//! For an image, `J_uu`, `J_vv` and `J_uv` are the sums of `g_u²`, `g_v²` and `g_u g_v` over
//! the interior pixels (central differences of the luminance), and the **diagonal
//! correlation** is `ρ = J_uv / √(J_uu J_vv)`: 0 for an isotropic texture or one whose
//! structures run along the axes, +1 for stripes whose gradient runs along (1, 1) (the lines
//! themselves along (1, −1)), −1 for the other diagonal. The blockiness figure counts how
//! much gradient energy lies along the axes; a photograph whose veins avoid the axes has a
//! low axis share, and a slice that loses the veins' diagonal preference shows up there as
//! "blocks" although it has no steps. This figure tells the two apart.
//!
//! **The sign bound.** A slice family sees the product of two world gradient components: the
//! slices ⊥ x see `g_y g_z`, ⊥ y `g_x g_z`, ⊥ z `g_x g_y` ([`ROLE_AXES`](crate::solid::ROLE_AXES)). A locally planar
//! structure (a vein sheet, a crack) with normal `n` has its gradient along `n`, and a tube
//! along its direction `t` shows in each slice along the projection of `t`; either way the
//! three families' signs multiply to `(n_x n_y)(n_y n_z)(n_x n_z) = (n_x n_y n_z)² ≥ 0`. So no
//! structure shows a negative diagonal in all three families at once: each contradicts at
//! least one. A volume can reach an exemplar's negative `ρ` on all three axes only as a
//! mixture of structures that each contradict one family, at best about a third of it. A
//! positive `ρ` has no such limit (sheets with normal (1, 1, 1) show it everywhere).
//! Mirroring one role's exemplar flips that role's sign and makes the product positive
//! (`solid/orientation.rs`); a mirrored photograph is a photograph of the same material.

use super::gradient_moments::{family_moments, moments};
use super::image::LinearImage;
use crate::solid::ROLES;

fn correlation([uu, vv, uv]: [f64; 3]) -> f64 {
    let norm = (uu * vv).sqrt();
    if norm > 0.0 {
        uv / norm
    } else {
        0.0
    }
}

/// The diagonal correlation `J_uv / √(J_uu J_vv)` of an image (module doc); 0 for a flat one.
pub fn diagonal_correlation(image: &LinearImage) -> f64 {
    correlation(moments(&image.luminance(), image.width, image.height))
}

/// The diagonal correlation of each slice family of a volume, from the sums over every
/// slice.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct VolumeDiagonal {
    /// `J_uv / √(J_uu J_vv)` over the slices ⊥ x, ⊥ y, ⊥ z, each in its role's image axes.
    pub axes: [f64; ROLES],
}

impl VolumeDiagonal {
    /// Measures an RGB cube of side `n`, x fastest, over the slices with a neighbour on both
    /// sides along the normal (as [`super::VolumeAnisotropy`] does).
    ///
    /// # Panics
    /// When `colours` does not hold `n³` voxels (a caller's bug).
    pub fn measure(colours: &[[u8; 3]], n: usize) -> VolumeDiagonal {
        let sums = family_moments(colours, n);
        VolumeDiagonal {
            axes: sums.map(correlation),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stripes whose grey level follows `x + sign · y` (gradient along (1, sign)).
    fn diagonal_stripes(n: usize, sign: i64) -> LinearImage {
        let rgb: Vec<[u8; 3]> = (0..n * n)
            .map(|k| {
                let (x, y) = ((k % n) as i64, (k / n) as i64);
                let t = (x + sign * y).rem_euclid(8);
                [if t < 4 { 40 } else { 200 }; 3]
            })
            .collect();
        LinearImage::from_rgb8(&rgb, n, n)
    }

    #[test]
    fn diagonal_stripes_have_their_sign_and_axis_stripes_none() {
        assert!(diagonal_correlation(&diagonal_stripes(32, 1)) > 0.9);
        assert!(diagonal_correlation(&diagonal_stripes(32, -1)) < -0.9);
        let rows: Vec<[u8; 3]> = (0..32 * 32)
            .map(|k| [((k / 32) * 29 % 256) as u8; 3])
            .collect();
        assert_eq!(
            diagonal_correlation(&LinearImage::from_rgb8(&rows, 32, 32)),
            0.0
        );
    }

    /// Sheets `n · p = const` with integer normal `normal` as a grey cube of side `side`.
    fn sheets(side: usize, normal: [i64; 3]) -> Vec<[u8; 3]> {
        (0..side * side * side)
            .map(|k| {
                let p = [k % side, (k / side) % side, k / (side * side)].map(|v| v as i64);
                let t = (0..3).map(|a| normal[a] * p[a]).sum::<i64>().rem_euclid(8);
                [if t < 4 { 40 } else { 200 }; 3]
            })
            .collect()
    }

    #[test]
    fn a_sheet_contradicts_a_negative_diagonal_in_at_least_one_family() {
        // Normal (1, 1, 1): every family positive.
        let v = VolumeDiagonal::measure(&sheets(24, [1, 1, 1]), 24);
        assert!(v.axes.iter().all(|&r| r > 0.9), "{v:?}");
        // Every sign pattern of the normal: the three signs multiply to a non-negative
        // number, so at most two families are negative.
        for normal in [[1, -1, 1], [1, 1, -1], [-1, 1, 1], [1, -1, -1]] {
            let v = VolumeDiagonal::measure(&sheets(24, normal), 24);
            let negative = v.axes.iter().filter(|&&r| r < -0.5).count();
            assert_eq!(negative, 2, "{normal:?}: {v:?}");
            assert!(v.axes.iter().product::<f64>() > 0.0, "{normal:?}: {v:?}");
        }
    }
}
