//! The candidates of every level computed natively on the host, exactly equal to
//! [`candidates_cpu`](super::candidates_cpu) (and so to the GPU kernels), but with searches that
//! skip what cannot be among the results. On a CPU device (lavapipe) this is what
//! `lazysolid solid` runs: the brute force spends most of its time on strips that a lower
//! bound already rules out.
//!
//! - **Strip search** (the S nearest strips of the target image to each query strip, ranked by
//!   (distance, pixel)): strips are 3N-value integer vectors, searched in an exact k-d tree
//!   built in the target strips' principal axes (`strip_tree.rs`).
//! - **Crossbar ranking** (the best 100 of the S² triples by (error, i·S + j)): every error,
//!   a row of S at a time, with the second list's strips held as columns so that one row is
//!   a loop over independent lanes; then a selection of the best 100. Bounds do not pay
//!   here: the two lists' own distances are small beside the third term (the distance of
//!   the two other strips), so at 256² 98 % of the pairs passed the sorted-list bound that
//!   an earlier pruned version used, and its per-pair branches cost more than the sums.
//! - **Strip distances** are exact sums of squares over zero-padded `f32` rows
//!   (`strip_tree::ssd`): integers below 2²⁴, so exact, and in independent lanes that the
//!   compiler vectorizes on any baseline.
//! - **Coherence filter**: per pixel the neighbours' coordinates of each other role are marked
//!   in a per-worker array of the exemplar's pixels, and a candidate is continued when one of
//!   its coordinate's four unit steps is marked (the same test as
//!   [`unit_step`](super::unit_step) against every neighbour candidate).

use super::analysis::{unpack_rgb, SolidAnalysis, SolidLevel};
use super::candidates::{
    build_levels, crossbar_pair, keep_rows, neighbours4, others, CandidateParams, CandidateSets,
    SearchKey, SolidCandidates, StripMatches, MAX_CANDIDATES,
};
use super::strip_tree::{distinct_strips, padded, padded_len, StripTree};
use super::strips::{along, sample_offset};
use crate::coords::{pack, unpack};
use crate::SynthResult;
use rayon::prelude::*;

/// Every pixel's strip along `axis` of an image's level colours: `n` RGB samples spaced by
/// `h`, as `3n` integers.
fn strips(colours: &[u32], axis: usize, n: u32, h: u32, m: u32) -> Vec<i32> {
    let mut out = Vec::with_capacity((m * m * 3 * n) as usize);
    for p in 0..m * m {
        for i in 0..n {
            let c = unpack_rgb(colours[along(p, axis, sample_offset(i, n, h), m) as usize]);
            out.extend(c.map(i32::from));
        }
    }
    out
}

/// The strip search of `search_cpu`, through a k-d tree of the target strips (module docs).
fn search_host(
    level: &SolidLevel,
    k: SearchKey,
    side: u32,
    params: &CandidateParams,
) -> StripMatches {
    let (n, h, m, s) = (params.strip, level.spacing, side, params.s as usize);
    let dims = 3 * n as usize;
    let queries = strips(&level.roles[k.query].colours, k.query_axis, n, h, m);
    let targets = strips(&level.roles[k.target].colours, k.target_axis, n, h, m);
    let tree = StripTree::new(&targets, dims);
    // Identical query strips have the same matches: each distinct one is searched once.
    let (distinct, members, first) = distinct_strips(&queries, dims);
    let found = tree.nearest_all(&distinct, s);
    let mut rows: Vec<&[(u32, u32)]> = vec![&[]; (m * m) as usize];
    for (u, row) in found.iter().enumerate() {
        for &p in &members[first[u] as usize..first[u + 1] as usize] {
            rows[p as usize] = row;
        }
    }
    StripMatches {
        s: s as u32,
        pixels: rows.iter().flat_map(|r| r.iter().map(|x| x.1)).collect(),
        distances: rows.iter().flat_map(|r| r.iter().map(|x| x.0)).collect(),
    }
}

/// Pairs of a crossbar row computed together: `j` lanes in independent accumulators, which
/// the compiler vectorizes on any baseline.
const BLOCK: usize = 8;

/// The strips of `pixels` transposed into `out`, `dims` rows of `columns` values: one strip
/// value of every pixel in one contiguous row. Columns past the pixels are never written, so
/// a buffer that starts zeroed and always receives as many pixels stays zero there.
fn transpose_into(
    strips: &[f32],
    stride: usize,
    dims: usize,
    pixels: &[u32],
    columns: usize,
    out: &mut [f32],
) {
    for (j, &q) in pixels.iter().enumerate() {
        let v = &strips[q as usize * stride..][..dims];
        for (d, &x) in v.iter().enumerate() {
            out[d * columns + j] = x;
        }
    }
}

/// The third terms of one crossbar row: the squared distances of strip `a` to every column
/// of `b` (`a.len()` rows of `columns` values), exact for the reason `strip_tree::ssd` is.
fn row_distances(a: &[f32], b: &[f32], columns: usize, out: &mut [f32]) {
    for (block, o) in out.chunks_exact_mut(BLOCK).enumerate() {
        let mut acc = [0.0f32; BLOCK];
        for (d, &x) in a.iter().enumerate() {
            let column = &b[d * columns + block * BLOCK..][..BLOCK];
            for k in 0..BLOCK {
                let t = x - column[k];
                acc[k] += t * t;
            }
        }
        o.copy_from_slice(&acc);
    }
}

/// The crossbar ranking of `triples_cpu`: all S² errors, a row at a time against the second
/// list's strips held as columns, then the best `kept` by (error, i·S + j) (module docs).
fn triples_host(
    level: &SolidLevel,
    e: usize,
    m1: &StripMatches,
    m2: &StripMatches,
    side: u32,
    params: &CandidateParams,
) -> CandidateSets {
    let ([f1, f2], [a1, a2]) = crossbar_pair(e);
    let (n, h, m, s) = (params.strip, level.spacing, side, params.s as usize);
    let dims = 3 * n as usize;
    let stride = padded_len(dims);
    let s1 = padded(&strips(&level.roles[f1].colours, a1, n, h, m), dims);
    let s2 = padded(&strips(&level.roles[f2].colours, a2, n, h, m), dims);
    let kept = params.kept();
    let columns = s.div_ceil(BLOCK) * BLOCK;
    let scratch = || {
        (
            vec![0.0f32; dims * columns],
            vec![0.0f32; columns],
            Vec::<u64>::with_capacity(s * s),
        )
    };
    let rows: Vec<Vec<(u32, [u32; 3])>> = (0..(m * m) as usize)
        .into_par_iter()
        .with_min_len(64)
        .map_init(scratch, |(b, third, keys), p| {
            let d1 = &m1.distances[p * s..][..s];
            let d2 = &m2.distances[p * s..][..s];
            transpose_into(&s2, stride, dims, &m2.pixels[p * s..][..s], columns, b);
            // Written in place (not pushed) so that the loop over `j` is vectorized.
            keys.resize(s * s, 0);
            for (i, (&di, row)) in d1.iter().zip(keys.chunks_exact_mut(s)).enumerate() {
                let q1 = m1.pixels[p * s + i] as usize;
                row_distances(&s1[q1 * stride..][..dims], b, columns, third);
                let rank = (i * s) as u64;
                for (j, ((&dj, &t), key)) in d2.iter().zip(third.iter()).zip(row).enumerate() {
                    *key = u64::from(di + dj + t as u32) << 32 | (rank + j as u64);
                }
            }
            if keys.len() > kept {
                keys.select_nth_unstable(kept - 1);
                keys.truncate(kept);
            }
            keys.sort_unstable();
            keys.iter()
                .map(|&key| {
                    let idx = (key & u64::from(u32::MAX)) as usize;
                    let (q1, q2) = (m1.pixels[p * s + idx / s], m2.pixels[p * s + idx % s]);
                    let mut t = [0u32; 3];
                    t[e] = pack(p as u32 % m, p as u32 / m);
                    t[f1] = pack(q1 % m, q1 / m);
                    t[f2] = pack(q2 % m, q2 / m);
                    ((key >> 32) as u32, t)
                })
                .collect()
        })
        .collect();
    CandidateSets {
        slots: kept,
        triples: rows.iter().flat_map(|r| r.iter().map(|x| x.1)).collect(),
        errors: rows.iter().flat_map(|r| r.iter().map(|x| x.0)).collect(),
        counts: rows.iter().map(|r| r.len() as u32).collect(),
    }
}

/// One coherence iteration of `coherence_step_cpu`, with the neighbours' coordinates looked up
/// in sorted lists (module docs).
fn coherence_step_host(sets: &CandidateSets, e: usize, h: u32, m: u32) -> (CandidateSets, u64) {
    let [f1, f2] = others(e);
    let slots = sets.slots;
    let index = |c: u32| {
        let (x, y) = unpack(c);
        y * m + x
    };
    // Per worker, one mark per exemplar pixel and other role: the pixel whose neighbours last
    // held that coordinate (a lookup instead of a sorted list per pixel).
    let marks = || {
        (
            vec![u32::MAX; (m * m) as usize],
            vec![u32::MAX; (m * m) as usize],
        )
    };
    let rows: Vec<(Vec<usize>, bool)> = (0..(m * m))
        .into_par_iter()
        .with_min_len(256)
        .map_init(marks, |(marks1, marks2), p| {
            let count = sets.counts[p as usize] as usize;
            if count <= MAX_CANDIDATES {
                return ((0..count).collect(), false);
            }
            for q in neighbours4(p, h, m) {
                for t in sets.of(q as usize) {
                    marks1[index(t[f1]) as usize] = p;
                    marks2[index(t[f2]) as usize] = p;
                }
            }
            let continued = |c: u32, marks: &[u32]| {
                neighbours4(index(c), h, m)
                    .iter()
                    .any(|&q| marks[q as usize] == p)
            };
            let kept: Vec<usize> = (0..count)
                .filter(|&k| {
                    let t = sets.triples[p as usize * slots + k];
                    continued(t[f1], marks1) && continued(t[f2], marks2)
                })
                .collect();
            if kept.is_empty() {
                ((0..MAX_CANDIDATES).collect(), true)
            } else {
                (kept, false)
            }
        })
        .collect();
    keep_rows(sets, rows)
}

/// The candidates of every level, computed on the host with pruned searches; equal to
/// [`candidates_cpu`](super::candidates_cpu) in every slot, error, count and report.
///
/// # Errors
/// Parameters out of range.
pub fn candidates_host(
    analysis: &SolidAnalysis,
    params: &CandidateParams,
    on_level: &mut dyn FnMut(u32),
) -> SynthResult<SolidCandidates> {
    let m = analysis.side;
    build_levels(
        analysis,
        params,
        on_level,
        |_| Ok::<_, crate::SynthError>(()),
        |_, level, k| Ok(search_host(level, k, m, params)),
        |_, level, e, m1, m2| Ok(triples_host(level, e, m1, m2, m, params)),
        |_, level, s, e| Ok(coherence_step_host(s, e, level.spacing, m)),
    )
}

/// Where the candidates are computed; both sides give the same candidates, bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CandidateBuilder {
    /// On the host on a CPU device (lavapipe: the pruned searches run natively, where the
    /// kernels' brute force is emulated SIMD), with the kernels on a GPU.
    #[default]
    Auto,
    /// [`candidates_host`].
    Host,
    /// [`GpuCandidates`](super::GpuCandidates).
    Gpu,
}

impl CandidateBuilder {
    /// `Host` or `Gpu`: what `Auto` means on `gpu`.
    pub fn resolve(self, gpu: &lazysolid_compute::gpu::Gpu) -> CandidateBuilder {
        match self {
            CandidateBuilder::Auto if gpu.info().is_cpu() => CandidateBuilder::Host,
            CandidateBuilder::Auto => CandidateBuilder::Gpu,
            chosen => chosen,
        }
    }

    /// `auto`, `host` or `gpu`: the word of the command line and the result files.
    pub fn name(self) -> &'static str {
        match self {
            CandidateBuilder::Auto => "auto",
            CandidateBuilder::Host => "host",
            CandidateBuilder::Gpu => "gpu",
        }
    }

    /// The candidates of every level, on the side this choice resolves to on `gpu`, with
    /// the usage balance of `params.balance` (`balance.rs`, a CPU pilot after the sets);
    /// `on_level` is called after each level of the sets, then of the pilot.
    ///
    /// # Errors
    /// Parameters out of range; device errors of the kernels.
    pub fn compute(
        self,
        gpu: &lazysolid_compute::gpu::Gpu,
        analysis: &SolidAnalysis,
        params: &CandidateParams,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<SolidCandidates> {
        let mut candidates = match self.resolve(gpu) {
            CandidateBuilder::Gpu => {
                super::GpuCandidates::new(gpu)?.compute(analysis, params, on_level)
            }
            _ => candidates_host(analysis, params, on_level),
        }?;
        super::balance::balance_finest_levels(
            analysis,
            &mut candidates,
            params.balance,
            params.balance_levels,
            on_level,
        )?;
        Ok(candidates)
    }
}
