//! Second moments of an image's luminance gradients, per image and per slice family of a
//! volume: what the anisotropy and the diagonal correlation are ratios of.

use super::image::LinearImage;
use crate::solid::{ROLES, ROLE_AXES};

/// `[J_uu, J_vv, J_uv]`: the sums of `g_u²`, `g_v²` and `g_u g_v` (central differences of the
/// luminance, halved) over the pixels of a `w`×`h` image with both neighbours on each axis.
pub(crate) fn moments(luma: &[f32], w: usize, h: usize) -> [f64; 3] {
    let mut j = [0.0f64; 3];
    if w < 3 || h < 3 {
        return j;
    }
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let at = |xx: usize, yy: usize| f64::from(luma[yy * w + xx]);
            let gu = 0.5 * (at(x + 1, y) - at(x - 1, y));
            let gv = 0.5 * (at(x, y + 1) - at(x, y - 1));
            j[0] += gu * gu;
            j[1] += gv * gv;
            j[2] += gu * gv;
        }
    }
    j
}

/// [`moments`] summed over every slice of each family of an RGB cube of side `n` (x fastest),
/// each slice in its role's image axes, over the slices with a neighbour on both sides along
/// the normal, so that the three families cover the same interior voxels.
///
/// # Panics
/// When `colours` does not hold `n³` voxels (a caller's bug).
pub(crate) fn family_moments(colours: &[[u8; 3]], n: usize) -> [[f64; 3]; ROLES] {
    assert_eq!(
        colours.len(),
        n * n * n,
        "voxel count of a cube of side {n}"
    );
    let mut sums = [[0.0f64; 3]; ROLES];
    let mut rgb = vec![[0u8; 3]; n * n];
    for (role, sum) in sums.iter_mut().enumerate() {
        let [a, b] = ROLE_AXES[role];
        for at in 1..n.saturating_sub(1) {
            for j in 0..n {
                for i in 0..n {
                    let mut p = [0usize; 3];
                    p[role] = at;
                    p[a] = i;
                    p[b] = j;
                    rgb[j * n + i] = colours[(p[2] * n + p[1]) * n + p[0]];
                }
            }
            let luma = LinearImage::from_rgb8(&rgb, n, n).luminance();
            let m = moments(&luma, n, n);
            (0..3).for_each(|k| sum[k] += m[k]);
        }
    }
    sums
}
