//! The candidates of every level computed natively on the host, exactly equal to
//! [`candidates_cpu`](super::candidates_cpu) (and so to the GPU kernels), but with searches that
//! skip what cannot be among the results. On a CPU device (lavapipe) this is what
//! `lazysolid solid` runs: the brute force spends most of its time on strips that a lower
//! bound already rules out.
//!
//! - **Strip search** (the S nearest strips of the target image to each query strip, ranked by
//!   (distance, pixel)): strips are 3N-value integer vectors, searched in an exact k-d tree
//!   built in the target strips' principal axes (`strip_tree.rs`).
//! - **Crossbar ranking** (the best 100 of the S² triples by (error, i·S + j)): both strip lists
//!   are sorted by distance, and `d1[i] + d2[j]` is a lower bound of the triple's error, so a
//!   row stops at the first `j` whose bound reaches the current 100th error, and the rows stop
//!   at the first `i` whose bound with `j = 0` does (pairs come in increasing rank, so reaching
//!   the worst error is enough: ties rank after it). The third term, the distance of the two
//!   other strips, is bounded below by their per-channel sums and slopes (`StripMoments`):
//!   a pair whose bound already reaches the worst error is skipped without its `3N`-value
//!   distance, which removes about two thirds of them.
//! - **Strip distances** are exact sums of squares over zero-padded `f32` rows
//!   ([`ssd`](super::strip_tree)): integers below 2²⁴, so exact, and in independent lanes that
//!   the compiler vectorizes on any baseline.
//! - **Coherence filter**: per pixel the neighbours' coordinates of each other role are marked
//!   in a per-worker array of the exemplar's pixels, and a candidate is continued when one of
//!   its coordinate's four unit steps is marked (the same test as
//!   [`unit_step`](super::unit_step) against every neighbour candidate).

use super::analysis::{unpack_rgb, SolidAnalysis, SolidLevel};
use super::candidates::{
    build_levels, crossbar_pair, keep_rows, neighbours4, others, CandidateParams, CandidateSets,
    SearchKey, SolidCandidates, StripMatches, MAX_CANDIDATES,
};
use super::strip_tree::{distinct_strips, padded, padded_len, ssd, StripTree};
use super::strips::{along, sample_offset};
use crate::coords::{pack, unpack};
use crate::SynthResult;
use rayon::prelude::*;
use std::collections::BinaryHeap;

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
    let found: Vec<Vec<(u32, u32)>> = distinct
        .par_chunks_exact(dims)
        .map(|query| tree.nearest(query, s))
        .collect();
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

/// Per strip, the projections of its samples onto two orthogonal directions per colour
/// channel: the constant (the channel's sum) and the centred ramp `i - (n - 1) / 2` (its
/// slope). By Bessel's inequality the squared differences of these projections, each divided
/// by its direction's squared length, sum to at most the strips' squared distance: a lower
/// bound of the crossbar's third term that costs six products instead of `3n`.
struct StripMoments {
    /// `[sum_r, sum_g, sum_b, ramp_r, ramp_g, ramp_b]` of every pixel's strip, each value
    /// already divided by the square root of its direction's squared length, so that the
    /// bound is the plain squared distance of two moment vectors.
    moments: Vec<[f32; 6]>,
}

impl StripMoments {
    fn new(strips: &[i32], n: usize) -> StripMoments {
        let centre = (n as f32 - 1.0) / 2.0;
        let ramp: f32 = (0..n).map(|i| (i as f32 - centre).powi(2)).sum();
        let (cs, rs) = (1.0 / (n as f32).sqrt(), 1.0 / ramp.max(1.0).sqrt());
        let moments = strips
            .chunks_exact(3 * n)
            .map(|v| {
                let mut m = [0f32; 6];
                for (i, c) in v.chunks_exact(3).enumerate() {
                    let r = i as f32 - centre;
                    for k in 0..3 {
                        m[k] += c[k] as f32;
                        m[3 + k] += r * c[k] as f32;
                    }
                }
                for k in 0..3 {
                    m[k] *= cs;
                    m[3 + k] *= rs;
                }
                m
            })
            .collect();
        StripMoments { moments }
    }
}

/// The moment bounds of one strip against a row of strips given as six columns, into `out`
/// (a loop over independent lanes, which the compiler vectorizes).
fn moment_bounds(a: &[f32; 6], columns: &[Vec<f32>; 6], out: &mut [f32]) {
    out.iter_mut().for_each(|o| *o = 0.0);
    for (k, column) in columns.iter().enumerate() {
        for (o, &b) in out.iter_mut().zip(column) {
            let d = a[k] - b;
            *o += d * d;
        }
    }
}

/// Whether a pair's third term, at least `bound` up to `f32` rounding, certainly brings its
/// error to `slack + 1` or more above the first two terms. Moments of different strips differ
/// by at least `1 / sqrt(ramp)` or not at all, and their rounding is below 10⁻⁶ relative, so
/// the margins (10⁻⁴ relative and 10⁻² absolute) keep every pair that could enter.
fn ruled_out(bound: f32, slack: i64) -> bool {
    f64::from(bound) * (1.0 - 1e-4) - 1e-2 > slack as f64 + 1.0
}

/// The crossbar ranking of `triples_cpu`, pruned by the sorted strip distances and a lower
/// bound of the third term (module docs).
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
    let raw1 = strips(&level.roles[f1].colours, a1, n, h, m);
    let raw2 = strips(&level.roles[f2].colours, a2, n, h, m);
    let (k1, k2) = (
        StripMoments::new(&raw1, n as usize),
        StripMoments::new(&raw2, n as usize),
    );
    let (s1, s2) = (padded(&raw1, dims), padded(&raw2, dims));
    let kept = params.kept();
    let rows: Vec<Vec<(u32, u32, [u32; 3])>> = (0..(m * m) as usize)
        .into_par_iter()
        .map(|p| {
            let mut heap: BinaryHeap<(u32, u32)> = BinaryHeap::with_capacity(kept + 1);
            let d1 = &m1.distances[p * s..][..s];
            let d2 = &m2.distances[p * s..][..s];
            let q2s = &m2.pixels[p * s..][..s];
            let columns: [Vec<f32>; 6] =
                std::array::from_fn(|k| q2s.iter().map(|&q| k2.moments[q as usize][k]).collect());
            let mut lower = vec![0f32; s];
            // Pairs are visited in increasing rank `i·S + j`, so a pair whose error can only
            // equal the current worst ranks after it: `>=` prunes ties as well.
            let worst = |heap: &BinaryHeap<(u32, u32)>| {
                if heap.len() == kept {
                    heap.peek().expect("full").0
                } else {
                    u32::MAX
                }
            };
            for (i, &di) in d1.iter().enumerate() {
                if u64::from(di) + u64::from(d2[0]) >= u64::from(worst(&heap)) {
                    break;
                }
                let q1 = m1.pixels[p * s + i] as usize;
                let v1 = &s1[q1 * stride..][..stride];
                moment_bounds(&k1.moments[q1], &columns, &mut lower);
                for (j, &dj) in d2.iter().enumerate() {
                    let w = worst(&heap);
                    let bound = di + dj;
                    if u64::from(bound) >= u64::from(w) {
                        break;
                    }
                    // Skip the pair when its third term alone brings it to the worst kept
                    // error (which, by the rank order, it cannot then beat).
                    if ruled_out(lower[j], i64::from(w) - i64::from(bound) - 1) {
                        continue;
                    }
                    let q2 = q2s[j] as usize;
                    let entry = (
                        bound + ssd(v1, &s2[q2 * stride..][..stride]),
                        (i * s + j) as u32,
                    );
                    if heap.len() < kept {
                        heap.push(entry);
                    } else if entry < *heap.peek().expect("full") {
                        *heap.peek_mut().expect("full") = entry;
                    }
                }
            }
            heap.into_sorted_vec()
                .into_iter()
                .map(|(cb, idx)| {
                    let (i, j) = (idx as usize / s, idx as usize % s);
                    let (q1, q2) = (m1.pixels[p * s + i], m2.pixels[p * s + j]);
                    let mut t = [0u32; 3];
                    t[e] = pack(p as u32 % m, p as u32 / m);
                    t[f1] = pack(q1 % m, q1 / m);
                    t[f2] = pack(q2 % m, q2 / m);
                    (cb, idx, t)
                })
                .collect()
        })
        .collect();
    CandidateSets {
        slots: kept,
        triples: rows.iter().flat_map(|r| r.iter().map(|x| x.2)).collect(),
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
        super::balance::balance_usage(analysis, &mut candidates, params.balance, on_level)?;
        Ok(candidates)
    }
}
