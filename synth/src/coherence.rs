//! k-coherence similarity sets (Tong et al. 2002, as used by Lefebvre & Hoppe): for every
//! exemplar pixel `u`, `C_1(u) = u` and `C_2..k(u)` are the pixels whose appearance vectors are
//! nearest to `u`'s, spread over the exemplar: each chosen pixel lies at least `spread` pixels
//! (toroidal Chebyshev distance) from `u` and from every other chosen one, so the set offers
//! genuinely different places to copy from.
//!
//! The search is brute force over a pool of candidate pixels: every pixel when the exemplar has
//! at most [`MAX_POOL`] pixels, otherwise a regular subgrid (every s-th row and column) of at
//! most that many. When no pixel satisfies the spread (tiny exemplars, large k), the slot
//! repeats `u`, which is harmless: the correction pass then just sees a duplicate candidate.

use super::appearance::{appearance_distance, APPEARANCE_DIMS};
use super::coords::{pack, torus_distance};
use rayon::prelude::*;

/// Most pixels the brute-force search compares each pixel against.
pub const MAX_POOL: usize = 4096;

/// The similarity sets of a `w`×`h` level: `k` packed coordinates per pixel, row-major.
pub fn coherence_sets(
    vectors: &[[i8; APPEARANCE_DIMS]],
    w: u32,
    h: u32,
    k: u32,
    spread: u32,
) -> Vec<u32> {
    let mut stride = 1;
    while (w.div_ceil(stride) * h.div_ceil(stride)) as usize > MAX_POOL {
        stride += 1;
    }
    let pool: Vec<(u32, u32)> = (0..h)
        .step_by(stride as usize)
        .flat_map(|y| (0..w).step_by(stride as usize).map(move |x| (x, y)))
        .collect();
    let far = |a: (u32, u32), b: (u32, u32)| torus_distance(a, b, w, h) >= spread;
    let mut sets = vec![0u32; (w * h * k) as usize];
    sets.par_chunks_mut(k as usize).enumerate().for_each_init(
        || vec![0u32; pool.len()],
        |dist, (i, set)| {
            let u = (i as u32 % w, i as u32 / w);
            let vu = &vectors[i];
            for (d, &(x, y)) in dist.iter_mut().zip(&pool) {
                *d = appearance_distance(vu, &vectors[(y * w + x) as usize]);
            }
            let mut chosen = vec![u];
            set[0] = pack(u.0, u.1);
            for slot in set.iter_mut().skip(1) {
                let mut best: Option<(u32, usize)> = None;
                for (j, &v) in pool.iter().enumerate() {
                    if best.is_some_and(|(bd, _)| dist[j] >= bd) {
                        continue;
                    }
                    if chosen.iter().all(|&c| far(v, c)) {
                        best = Some((dist[j], j));
                    }
                }
                let v = best.map_or(u, |(_, j)| pool[j]);
                chosen.push(v);
                *slot = pack(v.0, v.1);
            }
        },
    );
    sets
}
