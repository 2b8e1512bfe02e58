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
//!   row stops at the first `j` whose bound exceeds the current 100th error, and the rows stop
//!   at the first `i` whose bound with `j = 0` does.
//! - **Coherence filter**: per pixel the neighbours' coordinates of each other role go into a
//!   sorted list, and a candidate is continued when one of its coordinate's four unit steps is
//!   found there (the same test as [`unit_step`](super::unit_step) against every neighbour
//!   candidate).

use super::analysis::{unpack_rgb, SolidAnalysis, SolidLevel};
use super::candidates::{
    crossbar_pair, image_key, keep_rows, level_sets, neighbours4, others, search_key,
    CandidateParams, CandidateSets, LevelReport, SearchKey, SolidCandidates, StripMatches,
    MAX_CANDIDATES,
};
use super::roles::ROLES;
use super::strip_tree::{distinct_strips, ssd, StripTree};
use super::strips::{along, sample_offset};
use crate::synth::coords::{pack, unpack};
use crate::synth::SynthResult;
use rayon::prelude::*;
use std::collections::{BinaryHeap, HashMap};

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

/// The crossbar ranking of `triples_cpu`, pruned by the sorted strip distances (module docs).
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
    let s1 = strips(&level.roles[f1].colours, a1, n, h, m);
    let s2 = strips(&level.roles[f2].colours, a2, n, h, m);
    let kept = params.kept();
    let rows: Vec<Vec<(u32, u32, [u32; 3])>> = (0..(m * m) as usize)
        .into_par_iter()
        .map(|p| {
            let mut heap: BinaryHeap<(u32, u32)> = BinaryHeap::with_capacity(kept + 1);
            let d1 = &m1.distances[p * s..][..s];
            let d2 = &m2.distances[p * s..][..s];
            for (i, &di) in d1.iter().enumerate() {
                if heap.len() == kept && di + d2[0] > heap.peek().expect("full").0 {
                    break;
                }
                let q1 = m1.pixels[p * s + i] as usize;
                let v1 = &s1[q1 * dims..][..dims];
                for (j, &dj) in d2.iter().enumerate() {
                    let bound = di + dj;
                    if heap.len() == kept && bound > heap.peek().expect("full").0 {
                        break;
                    }
                    let q2 = m2.pixels[p * s + j] as usize;
                    let entry = (
                        bound + ssd(v1, &s2[q2 * dims..][..dims]),
                        (i * s + j) as u32,
                    );
                    if heap.len() < kept {
                        heap.push(entry);
                    } else if entry < *heap.peek().expect("full") {
                        heap.pop();
                        heap.push(entry);
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
    let rows: Vec<(Vec<usize>, bool)> = (0..(m * m))
        .into_par_iter()
        .map(|p| {
            let count = sets.counts[p as usize] as usize;
            if count <= MAX_CANDIDATES {
                return ((0..count).collect(), false);
            }
            let near = neighbours4(p, h, m);
            let coordinates = |role: usize| {
                let mut v: Vec<u32> = near
                    .iter()
                    .flat_map(|&q| sets.of(q as usize).iter().map(move |t| index(t[role])))
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            };
            let (c1, c2) = (coordinates(f1), coordinates(f2));
            let continued = |c: u32, list: &[u32]| {
                neighbours4(index(c), h, m)
                    .iter()
                    .any(|q| list.binary_search(q).is_ok())
            };
            let kept: Vec<usize> = (0..count)
                .filter(|&k| {
                    let t = sets.triples[p as usize * slots + k];
                    continued(t[f1], &c1) && continued(t[f2], &c2)
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
    params.check()?;
    let m = analysis.side;
    let mut levels = Vec::new();
    let mut reports = Vec::new();
    for (l, level) in analysis.levels.iter().enumerate() {
        let mut memo: HashMap<SearchKey, StripMatches> = HashMap::new();
        for e in 0..ROLES {
            for f in others(e) {
                let k = search_key(e, f);
                memo.entry(image_key(analysis, k))
                    .or_insert_with(|| search_host(level, k, m, params));
            }
        }
        let mut report = LevelReport::default();
        let sets = level_sets(
            analysis,
            &memo,
            params,
            &mut report,
            |e, m1, m2| {
                Ok::<_, crate::synth::SynthError>(triples_host(level, e, m1, m2, m, params))
            },
            |s, e| Ok(coherence_step_host(s, e, level.spacing, m)),
        )?;
        levels.push(sets);
        reports.push(report);
        on_level(l as u32);
    }
    Ok(SolidCandidates { levels, reports })
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
    pub fn resolve(self, gpu: &crate::gpu::Gpu) -> CandidateBuilder {
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

    /// The candidates of every level, on the side this choice resolves to on `gpu`.
    ///
    /// # Errors
    /// Parameters out of range; device errors of the kernels.
    pub fn compute(
        self,
        gpu: &crate::gpu::Gpu,
        analysis: &SolidAnalysis,
        params: &CandidateParams,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<SolidCandidates> {
        match self.resolve(gpu) {
            CandidateBuilder::Gpu => {
                super::GpuCandidates::new(gpu)?.compute(analysis, params, on_level)
            }
            _ => candidates_host(analysis, params, on_level),
        }
    }
}
