//! The CPU reference synthesizer: the same integer operations as the GPU kernels in
//! `glsl/synth/`, in plain Rust, so tests can demand that both agree exactly.

use super::analysis::{ExemplarAnalysis, LevelAnalysis};
use super::coords::{pack, unpack};
use super::error::SynthResult;
use super::jitter::jitter;
use super::neighbourhood::{neighbourhood_distance, shifted, synthesized_neighbourhood};
use super::params::SynthParams;
use super::period::{period_reach, spans_period};
use super::plan::{plan_regions, Region, SUBPASSES};
use super::synthesis::{check_window, LevelCoords, Synthesis};

/// Parity classes in subpass order.
pub(crate) const CLASSES: [[i32; 2]; SUBPASSES as usize] = [[0, 0], [1, 0], [0, 1], [1, 1]];

/// Upsampled (or, at level 0, initial) and jittered coordinates of `region` at `level`.
pub fn upsample_jitter(
    analysis: &ExemplarAnalysis,
    params: &SynthParams,
    level: u32,
    region: Region,
    parent: Option<&LevelCoords>,
) -> Vec<u32> {
    let (w, h) = (analysis.width, analysis.height);
    let spacing = analysis.levels[level as usize].spacing;
    let mut out = Vec::with_capacity(region.pixels());
    for iy in 0..region.size[1] as i32 {
        for ix in 0..region.size[0] as i32 {
            let (px, py) = (region.origin[0] + ix, region.origin[1] + iy);
            let (cx, cy) = match parent {
                None => (
                    (px.rem_euclid(w as i32) as u32 * spacing) % w,
                    (py.rem_euclid(h as i32) as u32 * spacing) % h,
                ),
                Some(parent) => {
                    let (qx, qy) = (px.div_euclid(2), py.div_euclid(2));
                    let pr = parent.region;
                    let i = (qy - pr.origin[1]) as usize * pr.size[0] as usize
                        + (qx - pr.origin[0]) as usize;
                    let (x, y) = unpack(parent.coords[i]);
                    (
                        (x + spacing * (px & 1) as u32) % w,
                        (y + spacing * (py & 1) as u32) % h,
                    )
                }
            };
            let j = jitter(
                px,
                py,
                level,
                params.seed,
                spacing,
                params.jitter[level as usize],
            );
            out.push(pack(
                (cx as i32 + j[0] + w as i32) as u32 % w,
                (cy as i32 + j[1] + h as i32) as u32 % h,
            ));
        }
    }
    out
}

/// One correction subpass: every pixel of parity `class` not on the region's border gets the
/// candidate whose exemplar neighbourhood best matches its synthesized one (the 4-diagonal,
/// 3-prediction neighbourhood of `neighbourhood.rs`, plus `period_penalty` for a candidate
/// that would make its coherent patch span an exemplar period, `period.rs`; ties keep the
/// current coordinate, then go to the smallest packed coordinate).
pub fn correct_subpass(
    analysis: &ExemplarAnalysis,
    level: u32,
    region: Region,
    coords: &mut [u32],
    class: [i32; 2],
    period_penalty: u32,
) {
    let lv: &LevelAnalysis = &analysis.levels[level as usize];
    let (w, h, k) = (analysis.width, analysis.height, analysis.k as usize);
    let s = lv.spacing as i32;
    let appearance = |c: u32| {
        let (x, y) = unpack(c);
        lv.appearance[(y * w + x) as usize]
    };
    let reach = period_reach(lv.spacing, w, h);
    let penalize = period_penalty != 0 && reach != [0, 0];
    let rw = region.size[0] as usize;
    for iy in 1..region.size[1] as i32 - 1 {
        for ix in 1..region.size[0] as i32 - 1 {
            if (region.origin[0] + ix) & 1 != class[0] || (region.origin[1] + iy) & 1 != class[1] {
                continue;
            }
            let mut around = [0u32; 9];
            for (n, (dx, dy)) in offsets().enumerate() {
                around[n] = coords[(iy + dy) as usize * rw + (ix + dx) as usize];
            }
            let synthesized = synthesized_neighbourhood(&around, appearance, s, w, h);
            // Ranked by (distance, 0 for the current coordinate else 1 + packed candidate):
            // the current coordinate survives every tie, so zero jitter keeps the tiling.
            let current = around[4];
            let mut best = (u32::MAX, u32::MAX, current);
            for (n, (dx, dy)) in offsets().enumerate() {
                let (x, y) = unpack(shifted(around[n], -dx, -dy, s, w, h));
                let base = (y * w + x) as usize;
                for &candidate in &lv.coherence[base * k..][..k] {
                    let (cx, cy) = unpack(candidate);
                    let mut d = neighbourhood_distance(
                        &synthesized,
                        &lv.neighbourhoods[(cy * w + cx) as usize],
                    );
                    if penalize && spans_period(candidate, &around, s, w, h, reach) {
                        d += period_penalty;
                    }
                    let rank = if candidate == current {
                        0
                    } else {
                        candidate + 1
                    };
                    best = best.min((d, rank, candidate));
                }
            }
            coords[iy as usize * rw + ix as usize] = best.2;
        }
    }
}

/// The 3×3 offsets, row by row (index 4 is the centre).
pub(crate) fn offsets() -> impl Iterator<Item = (i32, i32)> {
    (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)))
}

/// Synthesizes `window` (a region of the finest level) on the CPU, keeping every level.
///
/// # Errors
/// A window or parameter set that does not fit the analysis (see [`check_window`]).
pub fn synthesize_cpu(
    analysis: &ExemplarAnalysis,
    params: &SynthParams,
    window: Region,
) -> SynthResult<Synthesis> {
    check_window(analysis, params, window)?;
    let regions = plan_regions(window, &params.passes);
    let mut levels: Vec<LevelCoords> = Vec::with_capacity(regions.len());
    for (l, &region) in regions.iter().enumerate() {
        let l = l as u32;
        let mut coords = upsample_jitter(analysis, params, l, region, levels.last());
        for _ in 0..params.passes[l as usize] {
            for class in CLASSES {
                correct_subpass(
                    analysis,
                    l,
                    region,
                    &mut coords,
                    class,
                    params.period_penalty,
                );
            }
        }
        levels.push(LevelCoords { region, coords });
    }
    Ok(Synthesis { window, levels })
}
