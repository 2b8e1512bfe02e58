//! The candidate slab (thesis Fig. 3.25): `E_z` thickened along z with each pixel's first
//! candidate. The candidate's `E_x` and `E_y` neighbourhoods are orthogonal to `E_z` and meet
//! along the z line through the pixel, so both predict the voxels above and below it; a layer
//! at height `t` shows, per pixel, the median rule over `E_x[c_x + t·v]`, `E_y[c_y + t·v]` and
//! the pixel itself (at `t = 0` the crossbar's agreement decides). Coherent structures in the
//! layers away from 0 are what makes the candidates useful; noise means they are not.

use super::candidates::SolidCandidates;
use super::roles::SolidExemplars;
use super::volume::voxel_colour;
use crate::coords::pack;
use crate::neighbourhood::shifted;

/// The slab's `2 · half + 1` layers (heights `-half..=half`) side by side with a 2-pixel gap,
/// from the finest level's first candidates: width, height and RGB pixels.
pub fn candidate_slab(
    exemplars: &SolidExemplars,
    candidates: &SolidCandidates,
    half: u32,
) -> (u32, u32, Vec<[u8; 3]>) {
    let m = exemplars.side();
    let sets = &candidates.levels.last().expect("at least one level")[2];
    let layers = 2 * half + 1;
    let gap = 2;
    let width = layers * m + (layers - 1) * gap;
    let mut rgb = vec![[255u8; 3]; (width * m) as usize];
    for (layer, t) in (-(half as i32)..=half as i32).enumerate() {
        for p in 0..m * m {
            let first = sets.of(p as usize)[0];
            let triple = [
                shifted(first[0], 0, t, 1, m, m),
                shifted(first[1], 0, t, 1, m, m),
                pack(p % m, p / m),
            ];
            let x = layer as u32 * (m + gap) + p % m;
            rgb[((p / m) * width + x) as usize] = voxel_colour(exemplars, triple);
        }
    }
    (width, m, rgb)
}
