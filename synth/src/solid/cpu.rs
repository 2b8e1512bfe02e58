//! The CPU reference of the volume synthesizer: the same integer operations as
//! `glsl/synth/solid/upsample_jitter.comp` and `correct.comp`.
//!
//! Per level: each voxel's triple is its parent's plus `h_l` times the child offset projected
//! into each role (level 0: the projection of the position times `h_0`), then moved by the
//! projected 3D jitter. Then `P_l` passes of 8 subpasses, one per 2×2×2 parity class in the
//! order of `plan.rs`: every voxel of the class in the subpass's box takes, among its current
//! triple and the candidates gathered in each role's plane (for each of the 3×3 voxels of the
//! plane through the voxel perpendicular to the role's axis, that voxel's coordinate in the
//! role shifted back by its offset in the plane, and that pixel's candidate triples: the 2D
//! synthesizer's k-coherence, once per plane), the one
//! minimizing the sum over the three planes through the voxel of the 2D synthesizer's
//! 4-diagonal appearance distance — plane ⊥ x compares the `E_x` coordinates of the voxels in
//! that plane with the candidate's `E_x` neighbourhood, and so on — plus each coordinate's
//! usage penalty (`balance.rs`). The current triple competes
//! only as one of the gathered candidates (unless [`SynthParams::keep_current`]). Ties keep
//! the current triple, then go to the smallest triple.

use super::analysis::SolidAnalysis;
use super::candidates::{others, SolidCandidates};
use super::jitter::jitter3;
use super::plan::{plan_levels, Subpass, VolumeBox};
use super::roles::{project, ROLES, ROLE_AXES};
use super::schedule::level_schedules;
use super::volume::{check_box, LevelTriples, SolidSynthesis};
use crate::appearance::APPEARANCE_DIMS;
use crate::coords::{pack, unpack};
use crate::neighbourhood::{
    neighbourhood_distance, shifted, synthesized_neighbourhood, NEIGHBOURHOOD_DIMS,
};
use crate::{SynthError, SynthParams, SynthResult};
use rayon::prelude::*;

/// Offset `n` of the 3×3×3 neighbourhood (x fastest; 13 is the centre).
pub(crate) fn offset27(n: usize) -> [i32; 3] {
    [n % 3, (n / 3) % 3, n / 9].map(|v| v as i32 - 1)
}

/// Packed coordinate `c` moved by `spacing · d` on the `m`×`m` torus.
fn moved(c: u32, d: [i32; 2], spacing: i32, m: u32) -> u32 {
    shifted(c, d[0], d[1], spacing, m, m)
}

/// Upsampled (level 0: initial) and jittered triples of `region` at `level`.
pub fn upsample_jitter_3d(
    analysis: &SolidAnalysis,
    params: &SynthParams,
    level: u32,
    region: VolumeBox,
    parent: Option<&LevelTriples>,
) -> Vec<[u32; 3]> {
    (0..region.voxels())
        .map(|i| {
            let p = region.position(i);
            let up = parent
                .map(|parent| parent.triples[parent.region.index(p.map(|v| v.div_euclid(2)))]);
            upsample_voxel(analysis, params, level, p, up)
        })
        .collect()
}

/// The upsampled and jittered triple of the voxel at absolute position `p` of `level`, from
/// its parent's final triple (`None` at level 0, where the triple is the projection of the
/// position times `h_0`). What lazy synthesis calls per voxel.
pub fn upsample_voxel(
    analysis: &SolidAnalysis,
    params: &SynthParams,
    level: u32,
    p: [i32; 3],
    parent: Option<[u32; 3]>,
) -> [u32; 3] {
    let m = analysis.side;
    let h = analysis.levels[level as usize].spacing as i32;
    let base: [u32; 3] = match parent {
        None => std::array::from_fn(|r| {
            let [a, b] = ROLE_AXES[r];
            let q = [p[a], p[b]].map(|v| (v.rem_euclid(m as i32) as u32 * h as u32) % m);
            q[0] | q[1] << 16
        }),
        Some(t) => std::array::from_fn(|r| moved(t[r], project(r, p.map(|v| v & 1)), h, m)),
    };
    let j = jitter3(
        p,
        level,
        params.seed,
        h as u32,
        params.jitter[level as usize],
    );
    std::array::from_fn(|r| moved(base[r], project(r, j), 1, m))
}

/// The synthesized neighbourhoods of the three planes through the voxel whose 27 neighbours'
/// triples are `around`.
pub(crate) fn plane_neighbourhoods(
    analysis: &SolidAnalysis,
    level: u32,
    around: &[[u32; 3]; 27],
) -> [[i16; NEIGHBOURHOOD_DIMS]; ROLES] {
    let lv = &analysis.levels[level as usize];
    let m = analysis.side;
    std::array::from_fn(|r| {
        let [a, b] = ROLE_AXES[r];
        let plane: [u32; 9] = std::array::from_fn(|n| {
            let mut d = [0i32; 3];
            d[a] = n as i32 % 3 - 1;
            d[b] = n as i32 / 3 - 1;
            around[((d[2] + 1) * 9 + (d[1] + 1) * 3 + d[0] + 1) as usize][r]
        });
        let appearance = |c: u32| -> [i8; APPEARANCE_DIMS] {
            let (x, y) = unpack(c);
            lv.roles[r].appearance[(y * m + x) as usize]
        };
        synthesized_neighbourhood(&plane, appearance, lv.spacing as i32, m, m)
    })
}

/// Distance of candidate `t` to the synthesized plane neighbourhoods, each role's usage
/// penalty included (`balance.rs`).
pub(crate) fn triple_distance(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    level: u32,
    planes: &[[i16; NEIGHBOURHOOD_DIMS]; ROLES],
    t: [u32; 3],
) -> u32 {
    (0..ROLES)
        .map(|r| role_distance(analysis, candidates, level, planes, r, t[r]))
        .sum()
}

/// Role `r`'s share of [`triple_distance`]: coordinate `c`'s neighbourhood against the plane
/// perpendicular to the role's axis, plus its usage penalty.
fn role_distance(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    level: u32,
    planes: &[[i16; NEIGHBOURHOOD_DIMS]; ROLES],
    r: usize,
    c: u32,
) -> u32 {
    let m = analysis.side;
    let (x, y) = unpack(c);
    let pixel = (y * m + x) as usize;
    neighbourhood_distance(
        &planes[r],
        &analysis.levels[level as usize].roles[r].neighbourhoods[pixel],
    ) + candidates.penalty(level as usize, r, pixel)
}

/// Mean distance of the final triples of a level's computed box (voxels whose 3×3×3
/// neighbourhood lies inside it), in integer arithmetic: what the usage balance scales its
/// penalties by.
pub(crate) fn mean_final_distance(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    level: u32,
    computed: &LevelTriples,
) -> u64 {
    let region = computed.region;
    let (sum, n) = (0..region.voxels())
        .into_par_iter()
        .map(|i| {
            let p = region.position(i);
            let inside = (0..3).all(|a| {
                p[a] > region.origin[a] && p[a] < region.origin[a] + region.size[a] as i32 - 1
            });
            if !inside {
                return (0u64, 0u64);
            }
            let around: [[u32; 3]; 27] = std::array::from_fn(|k| {
                let d = offset27(k);
                computed.triples[region.index([p[0] + d[0], p[1] + d[1], p[2] + d[2]])]
            });
            let planes = plane_neighbourhoods(analysis, level, &around);
            let d = triple_distance(analysis, candidates, level, &planes, around[13]);
            (u64::from(d), 1)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    sum / n.max(1)
}

/// Offsets of the 3×3 voxels of role `r`'s plane through a voxel (the role's normal
/// component zero), in the order the kernel visits them.
pub(crate) fn plane_offsets(r: usize) -> [[i32; 3]; 9] {
    let [a, b] = ROLE_AXES[r];
    std::array::from_fn(|n| {
        let mut d = [0i32; 3];
        d[a] = n as i32 % 3 - 1;
        d[b] = n as i32 / 3 - 1;
        d
    })
}

/// One correction subpass over `region`'s triples, in place: the voxels of the subpass's
/// class inside its update box, or (a parallel pass) every voxel of the box, read from the
/// state before the pass.
pub fn correct_subpass_3d(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    level: u32,
    region: VolumeBox,
    triples: &mut [[u32; 3]],
    subpass: Subpass,
    keep_current: bool,
) {
    let span = subpass.span();
    let updated_voxels: Vec<usize> = (0..span[2].1 as i32)
        .flat_map(|z| {
            (0..span[1].1 as i32).flat_map(move |y| {
                (0..span[0].1 as i32).map(move |x| {
                    [
                        span[0].0 + span[0].2 as i32 * x,
                        span[1].0 + span[1].2 as i32 * y,
                        span[2].0 + span[2].2 as i32 * z,
                    ]
                })
            })
        })
        .map(|p| region.index(p))
        .collect();
    // Voxels of one class only read voxels of other classes, so they update independently;
    // a parallel pass reads every voxel as it was before the pass.
    let before: Option<Vec<[u32; 3]>> = subpass.class.is_none().then(|| triples.to_vec());
    let read: &[[u32; 3]] = before.as_deref().unwrap_or(triples);
    let updated: Vec<[u32; 3]> = updated_voxels
        .par_iter()
        .map(|&i| {
            let p = region.position(i);
            let around: [[u32; 3]; 27] = std::array::from_fn(|n| {
                let d = offset27(n);
                read[region.index([p[0] + d[0], p[1] + d[1], p[2] + d[2]])]
            });
            correct_voxel(analysis, candidates, level, keep_current, &around)
        })
        .collect();
    for (i, t) in updated_voxels.into_iter().zip(updated) {
        triples[i] = t;
    }
}

/// The corrected triple of the voxel whose 3×3×3 neighbourhood (x fastest, 13 the centre)
/// holds `around`: the best candidate gathered in each role's plane, among which the current
/// triple competes only if it was gathered, or always with `keep_current` (module docs).
/// Only the 19 voxels of the three planes through the centre are read; the 8 corners may hold
/// anything. What lazy synthesis calls per voxel.
pub fn correct_voxel(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    level: u32,
    keep_current: bool,
    around: &[[u32; 3]; 27],
) -> [u32; 3] {
    let m = analysis.side;
    let h = analysis.levels[level as usize].spacing as i32;
    let sets = &candidates.levels[level as usize];
    let planes = plane_neighbourhoods(analysis, level, around);
    let current = around[13];
    // Without `keep_current` the start is "no best yet" (above every distance, rank of a
    // non-current triple), which the first gathered candidate replaces; the sets are never
    // empty, so the current triple stays only when it is gathered and wins.
    let mut best = if keep_current {
        (
            triple_distance(analysis, candidates, level, &planes, current),
            0u32,
            current,
        )
    } else {
        (u32::MAX, 1u32, current)
    };
    for r in 0..ROLES {
        // The role's shifted-back pixels, sorted so that a repeat (which has the same
        // candidates) follows its first and is skipped; a fixed array, no allocation per voxel.
        let mut bases = plane_offsets(r).map(|d| {
            let t = around[((d[2] + 1) * 9 + (d[1] + 1) * 3 + d[0] + 1) as usize];
            let back = project(r, d).map(|v| -v);
            let (x, y) = unpack(moved(t[r], back, h, m));
            y * m + x
        });
        bases.sort_unstable();
        for (i, &base) in bases.iter().enumerate() {
            if i > 0 && base == bases[i - 1] {
                continue;
            }
            // Every candidate of pixel `base` in role `r` has `base` as its role-`r` coordinate,
            // so that share of the distance is computed once per set; a partial sum above the
            // best distance cannot win (the shares are never negative), so the rest is skipped.
            // The choice is the full comparison's, bit for bit.
            let own_c = pack(base % m, base / m);
            let own = role_distance(analysis, candidates, level, &planes, r, own_c);
            if own > best.0 {
                continue;
            }
            'candidate: for &c in sets[r].of(base as usize) {
                debug_assert_eq!(c[r], own_c, "a candidate of pixel {base} in role {r}");
                let mut dist = own;
                for other in others(r) {
                    dist += role_distance(analysis, candidates, level, &planes, other, c[other]);
                    if dist > best.0 {
                        continue 'candidate;
                    }
                }
                best = best.min((dist, (c != current) as u32, c));
            }
        }
    }
    best.2
}

/// Synthesizes `window` of the finest level on the CPU, keeping every level.
///
/// # Errors
/// A window or parameter set that does not fit.
pub fn synthesize_solid_cpu(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    params: &SynthParams,
    window: VolumeBox,
) -> SynthResult<SolidSynthesis> {
    check_solid(analysis, candidates, params, window)?;
    let plans = plan_levels(window, &level_schedules(params));
    let mut levels: Vec<LevelTriples> = Vec::with_capacity(plans.len());
    for (l, plan) in plans.iter().enumerate() {
        let l = l as u32;
        let region = plan.region;
        let mut triples = upsample_jitter_3d(analysis, params, l, region, levels.last());
        for &subpass in &plan.subpasses {
            correct_subpass_3d(
                analysis,
                candidates,
                l,
                region,
                &mut triples,
                subpass,
                params.keep_current,
            );
        }
        levels.push(LevelTriples { region, triples });
    }
    Ok(SolidSynthesis { window, levels })
}

/// Checks that the window, the candidates and the parameters fit the analysis.
pub(crate) fn check_solid(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    params: &SynthParams,
    window: VolumeBox,
) -> SynthResult<()> {
    check_box(window)?;
    check_levels(analysis, candidates, params)
}

/// Checks that the candidates and the parameters have one entry per level of the analysis.
pub(crate) fn check_levels(
    analysis: &SolidAnalysis,
    candidates: &SolidCandidates,
    params: &SynthParams,
) -> SynthResult<()> {
    let levels = analysis.levels.len();
    for (name, n) in [
        ("candidate levels", candidates.levels.len()),
        ("passes", params.passes.len()),
        ("jitter", params.jitter.len()),
    ] {
        if n != levels {
            return Err(SynthError::Parameter {
                name,
                value: n.to_string(),
                limit: format!("the exemplars have {levels} levels"),
            });
        }
    }
    Ok(())
}
