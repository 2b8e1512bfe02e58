//! 3D candidates per pyramid level (Dong et al. 2008): for each pixel of each role a small set
//! of coordinate triples `(c_x, c_y, c_z)` whose three 2D neighbourhoods agree along their
//! crossbar and that form coherent patches with the candidates of neighbouring pixels.
//!
//! Per level and role `e` with the other roles `f1 < f2`:
//! 1. **Strip search**: for every pixel `p` of `E_e` the [`CandidateParams::s`] strips of
//!    `E_f1` (resp. `E_f2`) closest to `E_e`'s strip at `p` along the axis the two roles share,
//!    brute force, ranked by (distance, pixel index).
//! 2. **Crossbar**: all `S²` triples `(p, q1, q2)` scored by the full crossbar error
//!    `CB = d(e, f1) + d(e, f2) + d(f1, f2)` (the third term compares `q1`'s and `q2`'s strips
//!    along the axis `f1` and `f2` share); the [`KEPT`] best by (CB, `i·S + j`) are kept.
//! 3. **Coherence filter** (the thesis' update rule): a candidate of a pixel with more than
//!    [`MAX_CANDIDATES`] survives an iteration when, for each of its two other coordinates,
//!    some candidate of one of the pixel's 4 neighbours (`±h` in the image) has that
//!    coordinate one step (`±h` along one image axis, on the torus) away. All pixels update
//!    from the previous iteration's sets. Pixels with at most [`MAX_CANDIDATES`] are left as
//!    they are. **Fallback**: when no candidate of a pixel would survive, the pixel keeps its
//!    [`MAX_CANDIDATES`] best by CB instead (counted in [`LevelReport::fallbacks`]).
//!    Iterations stop when no pixel has more than [`MAX_CANDIDATES`], or after
//!    [`MAX_COHERENCE_ITERATIONS`]; then every set is cut to its [`MAX_CANDIDATES`] smallest
//!    crossbar errors (sets stay sorted by CB throughout).
//!
//! Everything is integer arithmetic with fixed tie-breaks, so the GPU (`candidates_gpu.rs`)
//! agrees exactly with this CPU reference.

use super::analysis::{SolidAnalysis, SolidLevel};
use super::roles::{image_axis, shared_axis, ROLES};
use super::strips::{strip_distance, DEFAULT_STRIP, MAX_STRIP};
use crate::coords::{pack, unpack};
use crate::{SynthError, SynthResult};
use rayon::prelude::*;
use std::collections::HashMap;

/// Default strips kept per other role (the thesis' S, "chosen to not miss any good triple").
pub const DEFAULT_S: u32 = 65;

/// Largest S (the GPU keeps the S best in a fixed array).
pub const MAX_S: u32 = crate::shader_constants::SOLID_MAX_S;

/// Triples kept per pixel after the crossbar ranking (the thesis' 100).
pub const KEPT: usize = crate::shader_constants::SOLID_KEPT as usize;

/// Candidates per pixel after the coherence filter (the thesis' 12).
pub const MAX_CANDIDATES: usize = crate::shader_constants::SOLID_MAX_CANDIDATES as usize;

/// Most coherence iterations (the thesis: "typically 2").
pub const MAX_COHERENCE_ITERATIONS: u32 = 4;

/// Choices of the candidate construction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CandidateParams {
    /// Strip length `N` (odd).
    pub strip: u32,
    /// Strips kept per other role, `S`.
    pub s: u32,
    /// Whether the coherence filter runs; without it each pixel keeps its
    /// [`MAX_CANDIDATES`] smallest crossbar errors (the "crossbar only" ablation).
    pub coherence: bool,
    /// Strength of the usage balance (`balance.rs`) that [`CandidateBuilder`] adds to the
    /// candidates; 0: none (the builders' own sets, as `bench solid`'s `no balance` ablation
    /// uses them).
    ///
    /// [`CandidateBuilder`]: super::CandidateBuilder
    pub balance: u32,
    /// The finest levels that get the usage balance's penalties (`None`: every level;
    /// `balance.rs`, [`balance_finest_levels`](super::balance_finest_levels)).
    pub balance_levels: Option<u32>,
}

impl Default for CandidateParams {
    fn default() -> Self {
        CandidateParams {
            strip: DEFAULT_STRIP,
            s: DEFAULT_S,
            coherence: true,
            balance: super::balance::DEFAULT_BALANCE,
            balance_levels: None,
        }
    }
}

impl CandidateParams {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] naming the parameter and its limit.
    pub fn check(&self) -> SynthResult<()> {
        if self.strip % 2 == 0 || !(1..=MAX_STRIP).contains(&self.strip) {
            return Err(SynthError::Parameter {
                name: "strip",
                value: self.strip.to_string(),
                limit: format!("must be odd and in 1..={MAX_STRIP}"),
            });
        }
        if !(1..=MAX_S).contains(&self.s) {
            return Err(SynthError::Parameter {
                name: "s",
                value: self.s.to_string(),
                limit: format!("must lie in 1..={MAX_S}"),
            });
        }
        if self.balance_levels == Some(0) {
            return Err(SynthError::Parameter {
                name: "balance levels",
                value: "0".to_string(),
                limit: "must be at least 1 (--balance 0 turns the balance off)".to_string(),
            });
        }
        if self.balance > super::balance::MAX_BALANCE {
            return Err(SynthError::Parameter {
                name: "balance",
                value: self.balance.to_string(),
                limit: format!("must lie in 0..={}", super::balance::MAX_BALANCE),
            });
        }
        Ok(())
    }

    /// Triples ranked per pixel: `min(KEPT, S²)`.
    pub fn kept(&self) -> usize {
        KEPT.min((self.s * self.s) as usize)
    }
}

/// The best strips of one role for every pixel of another: `s` per pixel, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StripMatches {
    /// Matches per pixel.
    pub s: u32,
    /// Pixel indices of the matching strips.
    pub pixels: Vec<u32>,
    /// Their strip distances.
    pub distances: Vec<u32>,
}

/// Candidate sets of one role: `slots` triples per pixel, the first `counts[p]` valid, sorted
/// by (crossbar error, rank).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CandidateSets {
    /// Slots per pixel.
    pub slots: usize,
    /// Packed coordinates `(c_x, c_y, c_z)` of each slot.
    pub triples: Vec<[u32; 3]>,
    /// Crossbar error of each slot.
    pub errors: Vec<u32>,
    /// Valid slots per pixel.
    pub counts: Vec<u32>,
}

impl CandidateSets {
    /// The valid triples of pixel `p`.
    pub fn of(&self, p: usize) -> &[[u32; 3]] {
        &self.triples[p * self.slots..][..self.counts[p] as usize]
    }

    /// The same sets cut to `slots` per pixel (each keeps its first `slots`).
    pub fn truncated(&self, slots: usize) -> CandidateSets {
        let pixels = self.counts.len();
        let mut out = CandidateSets {
            slots,
            triples: vec![[0; 3]; pixels * slots],
            errors: vec![0; pixels * slots],
            counts: self.counts.iter().map(|&c| c.min(slots as u32)).collect(),
        };
        for p in 0..pixels {
            let n = out.counts[p] as usize;
            out.triples[p * slots..][..n].copy_from_slice(&self.triples[p * self.slots..][..n]);
            out.errors[p * slots..][..n].copy_from_slice(&self.errors[p * self.slots..][..n]);
        }
        out
    }
}

/// What the coherence filter did at one level.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LevelReport {
    /// Most iterations any role needed.
    pub iterations: u32,
    /// Pixel sets (over all roles and iterations) that would have become empty and kept
    /// their best crossbar candidates instead.
    pub fallbacks: u64,
    /// Pixels (over all roles) that still had more than [`MAX_CANDIDATES`] after the last
    /// iteration and were cut by crossbar error.
    pub cut: u64,
    /// Candidates over all pixels and roles after the cut.
    pub candidates: u64,
}

/// The candidates of every level.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SolidCandidates {
    /// Per level (coarsest first) the sets of `E_x`, `E_y`, `E_z`, [`MAX_CANDIDATES`] slots.
    pub levels: Vec<[CandidateSets; ROLES]>,
    /// Per level, what the coherence filter did.
    pub reports: Vec<LevelReport>,
    /// Per level and role, the usage penalty of every exemplar pixel (`balance.rs`), added
    /// to that role's neighbourhood distance; empty: none.
    pub balance: Vec<[Vec<u32>; ROLES]>,
}

impl SolidCandidates {
    /// The usage penalty of `pixel` in `role` at `level` (0 without a balance).
    pub fn penalty(&self, level: usize, role: usize, pixel: usize) -> u32 {
        self.balance.get(level).map_or(0, |b| b[role][pixel])
    }
}

/// One strip search: query role, its image axis, target role, its image axis. Two searches
/// with the same images (by [`SolidAnalysis::role_image`]) and axes are the same search.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct SearchKey {
    pub query: usize,
    pub query_axis: usize,
    pub target: usize,
    pub target_axis: usize,
}

/// The search for role `e`'s strips in role `f` along the axis they share, and the key of
/// the images it actually compares.
pub(crate) fn search_key(e: usize, f: usize) -> SearchKey {
    let a = shared_axis(e, f);
    SearchKey {
        query: e,
        query_axis: image_axis(e, a).unwrap(),
        target: f,
        target_axis: image_axis(f, a).unwrap(),
    }
}

/// The image-identity of a search (roles replaced by their images).
pub(crate) fn image_key(analysis: &SolidAnalysis, k: SearchKey) -> SearchKey {
    SearchKey {
        query: analysis.role_image[k.query],
        target: analysis.role_image[k.target],
        ..k
    }
}

/// The other two roles of `e`, in increasing order.
pub(crate) fn others(e: usize) -> [usize; 2] {
    match e {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// The two other roles `[f1, f2]` of role `e` and the image axes `[a1, a2]` along which their
/// strips meet: the third pair of strips of `e`'s crossbar.
pub(crate) fn crossbar_pair(e: usize) -> ([usize; 2], [usize; 2]) {
    let [f1, f2] = others(e);
    let a = shared_axis(f1, f2);
    (
        [f1, f2],
        [image_axis(f1, a).unwrap(), image_axis(f2, a).unwrap()],
    )
}

/// CPU strip search (reference of `strip_search.comp`).
pub fn search_cpu(
    level: &SolidLevel,
    key_roles: (usize, usize, usize, usize),
    side: u32,
    params: &CandidateParams,
) -> StripMatches {
    let (e, ea, f, fa) = key_roles;
    let (a, b) = (&level.roles[e].colours, &level.roles[f].colours);
    let (n, h, m, s) = (params.strip, level.spacing, side, params.s as usize);
    let pixels = (m * m) as usize;
    let rows: Vec<Vec<(u32, u32)>> = (0..pixels as u32)
        .into_par_iter()
        .map(|p| {
            let mut all: Vec<(u32, u32)> = (0..m * m)
                .map(|q| (strip_distance(a, p, ea, b, q, fa, n, h, m), q))
                .collect();
            all.select_nth_unstable(s - 1);
            all.truncate(s);
            all.sort_unstable();
            all
        })
        .collect();
    StripMatches {
        s: s as u32,
        pixels: rows.iter().flat_map(|r| r.iter().map(|x| x.1)).collect(),
        distances: rows.iter().flat_map(|r| r.iter().map(|x| x.0)).collect(),
    }
}

/// CPU crossbar ranking of role `e` (reference of `triples.comp`): `m1`, `m2` are `e`'s
/// matches in its two other roles (increasing order).
pub fn triples_cpu(
    level: &SolidLevel,
    e: usize,
    m1: &StripMatches,
    m2: &StripMatches,
    side: u32,
    params: &CandidateParams,
) -> CandidateSets {
    let ([f1, f2], [a1, a2]) = crossbar_pair(e);
    let (c1, c2) = (&level.roles[f1].colours, &level.roles[f2].colours);
    let (n, h, m, s) = (params.strip, level.spacing, side, params.s as usize);
    let kept = params.kept();
    let rows: Vec<Vec<(u32, u32, [u32; 3])>> = (0..(m * m) as usize)
        .into_par_iter()
        .map(|p| {
            let mut all = Vec::with_capacity(s * s);
            for i in 0..s {
                let (q1, d1) = (m1.pixels[p * s + i], m1.distances[p * s + i]);
                for j in 0..s {
                    let (q2, d2) = (m2.pixels[p * s + j], m2.distances[p * s + j]);
                    let cb = d1 + d2 + strip_distance(c1, q1, a1, c2, q2, a2, n, h, m);
                    let mut t = [0u32; 3];
                    t[e] = pack(p as u32 % m, p as u32 / m);
                    t[f1] = pack(q1 % m, q1 / m);
                    t[f2] = pack(q2 % m, q2 / m);
                    all.push((cb, (i * s + j) as u32, t));
                }
            }
            all.select_nth_unstable_by_key(kept - 1, |x| (x.0, x.1));
            all.truncate(kept);
            all.sort_unstable_by_key(|x| (x.0, x.1));
            all
        })
        .collect();
    CandidateSets {
        slots: kept,
        triples: rows.iter().flat_map(|r| r.iter().map(|x| x.2)).collect(),
        errors: rows.iter().flat_map(|r| r.iter().map(|x| x.0)).collect(),
        counts: vec![kept as u32; (m * m) as usize],
    }
}

/// Whether packed coordinates `a` and `b` are one step `h` apart along one image axis of the
/// `m`×`m` torus (at `h = m` a step wraps onto the pixel itself).
pub fn unit_step(a: u32, b: u32, h: u32, m: u32) -> bool {
    let ((ax, ay), (bx, by)) = (unpack(a), unpack(b));
    let du = (bx + m - ax) % m;
    let dv = (by + m - ay) % m;
    let (s1, s2) = (h % m, (m - h % m) % m);
    (du == 0 && (dv == s1 || dv == s2)) || (dv == 0 && (du == s1 || du == s2))
}

/// The 4 neighbours of pixel `p` at distance `h` (order: −u, +u, −v, +v).
pub fn neighbours4(p: u32, h: u32, m: u32) -> [u32; 4] {
    use super::strips::along;
    let h = h as i32;
    [
        along(p, 0, -h, m),
        along(p, 0, h, m),
        along(p, 1, -h, m),
        along(p, 1, h, m),
    ]
}

/// One coherence iteration of role `e` (reference of `coherence.comp`); returns the new sets
/// and the number of pixels that fell back to their best crossbar candidates.
pub fn coherence_step_cpu(sets: &CandidateSets, e: usize, h: u32, m: u32) -> (CandidateSets, u64) {
    let [f1, f2] = others(e);
    let slots = sets.slots;
    let rows: Vec<(Vec<usize>, bool)> = (0..(m * m))
        .into_par_iter()
        .map(|p| {
            let count = sets.counts[p as usize] as usize;
            if count <= MAX_CANDIDATES {
                return ((0..count).collect(), false);
            }
            let near = neighbours4(p, h, m);
            let continued = |c: u32, role: usize| {
                near.iter().any(|&q| {
                    sets.of(q as usize)
                        .iter()
                        .any(|t| unit_step(c, t[role], h, m))
                })
            };
            let kept: Vec<usize> = (0..count)
                .filter(|&k| {
                    let t = sets.triples[p as usize * slots + k];
                    continued(t[f1], f1) && continued(t[f2], f2)
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

/// The sets that keep, per pixel, the slots `rows[p].0` of `sets` (in that order), and the
/// number of pixels whose row says they fell back: what one coherence iteration returns.
pub(crate) fn keep_rows(
    sets: &CandidateSets,
    rows: Vec<(Vec<usize>, bool)>,
) -> (CandidateSets, u64) {
    let slots = sets.slots;
    let mut out = CandidateSets {
        slots,
        triples: vec![[0; 3]; sets.triples.len()],
        errors: vec![0; sets.errors.len()],
        counts: vec![0; sets.counts.len()],
    };
    let mut fallbacks = 0;
    for (p, (kept, fell_back)) in rows.into_iter().enumerate() {
        fallbacks += fell_back as u64;
        out.counts[p] = kept.len() as u32;
        for (slot, k) in kept.into_iter().enumerate() {
            out.triples[p * slots + slot] = sets.triples[p * slots + k];
            out.errors[p * slots + slot] = sets.errors[p * slots + k];
        }
    }
    (out, fallbacks)
}

/// Runs the coherence iterations on `sets` with `step` (CPU or GPU) and cuts the result to
/// [`MAX_CANDIDATES`]; shared by both implementations so that the loop is the same.
pub(crate) fn filter_and_cut<E>(
    mut sets: CandidateSets,
    params: &CandidateParams,
    report: &mut LevelReport,
    mut step: impl FnMut(&CandidateSets) -> Result<(CandidateSets, u64), E>,
) -> Result<CandidateSets, E> {
    if params.coherence {
        let mut iterations = 0;
        while iterations < MAX_COHERENCE_ITERATIONS
            && sets.counts.iter().any(|&c| c as usize > MAX_CANDIDATES)
        {
            let (next, fallbacks) = step(&sets)?;
            sets = next;
            report.fallbacks += fallbacks;
            iterations += 1;
        }
        report.iterations = report.iterations.max(iterations);
    }
    report.cut += sets
        .counts
        .iter()
        .filter(|&&c| c as usize > MAX_CANDIDATES)
        .count() as u64;
    let cut = sets.truncated(MAX_CANDIDATES);
    report.candidates += cut.counts.iter().map(|&c| c as u64).sum::<u64>();
    Ok(cut)
}

/// The candidates of every level: per level, each distinct strip search once (searches that
/// compare the same two images share one result), then per role the crossbar ranking of its
/// two searches, the coherence iterations and the cut, with `on_level` called after each
/// level. Shared by the CPU reference, the host builder and the GPU kernels, so that the
/// sequence, and with it the report, is one; each supplies `prepare` (its per-level state,
/// e.g. the level's colours on the device), `search`, `rank` and `step`.
pub(crate) fn build_levels<S, M, E: From<SynthError>>(
    analysis: &SolidAnalysis,
    params: &CandidateParams,
    on_level: &mut dyn FnMut(u32),
    mut prepare: impl FnMut(&SolidLevel) -> Result<S, E>,
    mut search: impl FnMut(&S, &SolidLevel, SearchKey) -> Result<M, E>,
    mut rank: impl FnMut(&S, &SolidLevel, usize, &M, &M) -> Result<CandidateSets, E>,
    mut step: impl FnMut(&S, &SolidLevel, &CandidateSets, usize) -> Result<(CandidateSets, u64), E>,
) -> Result<SolidCandidates, E> {
    params.check()?;
    let mut levels = Vec::with_capacity(analysis.levels.len());
    let mut reports = Vec::with_capacity(analysis.levels.len());
    for (l, level) in analysis.levels.iter().enumerate() {
        let state = prepare(level)?;
        let mut memo: HashMap<SearchKey, M> = HashMap::new();
        for e in 0..ROLES {
            for f in others(e) {
                let k = search_key(e, f);
                let id = image_key(analysis, k);
                if let std::collections::hash_map::Entry::Vacant(slot) = memo.entry(id) {
                    slot.insert(search(&state, level, k)?);
                }
            }
        }
        let mut report = LevelReport::default();
        let mut sets = Vec::with_capacity(ROLES);
        for e in 0..ROLES {
            let [f1, f2] = others(e);
            let m1 = &memo[&image_key(analysis, search_key(e, f1))];
            let m2 = &memo[&image_key(analysis, search_key(e, f2))];
            let ranked = rank(&state, level, e, m1, m2)?;
            sets.push(filter_and_cut(ranked, params, &mut report, |s| {
                step(&state, level, s, e)
            })?);
        }
        levels.push(
            sets.try_into()
                .unwrap_or_else(|_| unreachable!("three roles")),
        );
        reports.push(report);
        on_level(l as u32);
    }
    Ok(SolidCandidates {
        levels,
        reports,
        balance: Vec::new(),
    })
}

/// The candidates of every level on the CPU (the reference of [`super::GpuCandidates`]).
///
/// # Errors
/// Parameters out of range.
pub fn candidates_cpu(
    analysis: &SolidAnalysis,
    params: &CandidateParams,
) -> SynthResult<SolidCandidates> {
    let m = analysis.side;
    build_levels(
        analysis,
        params,
        &mut |_| {},
        |_| Ok::<_, SynthError>(()),
        |_, level, k| {
            Ok(search_cpu(
                level,
                (k.query, k.query_axis, k.target, k.target_axis),
                m,
                params,
            ))
        },
        |_, level, e, m1, m2| Ok(triples_cpu(level, e, m1, m2, m, params)),
        |_, level, s, e| Ok(coherence_step_cpu(s, e, level.spacing, m)),
    )
}
