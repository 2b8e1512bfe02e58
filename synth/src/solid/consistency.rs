//! How consistent the synthesized triples are, the cheap checks behind the correction's rule:
//! a triple that is one of the precomputed candidates has three exemplar colours that agree
//! (their crossbars were matched), a triple that upsampling and jitter merely translated in
//! general does not, and the median rule then shows the disagreement as axis-aligned blocks.

use super::candidates::SolidCandidates;
use super::roles::{SolidExemplars, ROLES};
use super::volume::SolidSynthesis;
use crate::coords::unpack;

/// Consistency of the finest level's triples over a synthesized window.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct TripleConsistency {
    /// Share of the window's voxels whose triple is one of the candidates of its own pixel in
    /// some role.
    pub candidate_share: f64,
    /// Mean over the window's voxels of the colour spread of the triple: per channel the
    /// largest minus the smallest of the three exemplar colours, averaged over the channels
    /// (8-bit levels).
    pub spread: f64,
    /// The same mean over every candidate triple of the finest level: what a consistent
    /// triple's spread looks like for these exemplars.
    pub candidate_spread: f64,
}

/// The colour spread of triple `t` (see [`TripleConsistency::spread`]).
pub fn triple_spread(exemplars: &SolidExemplars, t: [u32; 3]) -> f64 {
    let c: [[u8; 3]; ROLES] = std::array::from_fn(|r| {
        let (x, y) = unpack(t[r]);
        exemplars.role(r).at(x, y)
    });
    (0..3)
        .map(|ch| {
            let v = [c[0][ch], c[1][ch], c[2][ch]];
            f64::from(v.iter().max().unwrap() - v.iter().min().unwrap())
        })
        .sum::<f64>()
        / 3.0
}

/// Measures the finest level of `synthesis` against the finest level's candidates.
pub fn triple_consistency(
    exemplars: &SolidExemplars,
    candidates: &SolidCandidates,
    synthesis: &SolidSynthesis,
) -> TripleConsistency {
    let sets = candidates.levels.last().expect("a finest level");
    let m = exemplars.side();
    let triples = synthesis.window_triples();
    let is_candidate = |t: [u32; 3]| {
        (0..ROLES).any(|r| {
            let (x, y) = unpack(t[r]);
            sets[r].of((y * m + x) as usize).contains(&t)
        })
    };
    let n = triples.len().max(1) as f64;
    let share = triples.iter().filter(|&&t| is_candidate(t)).count() as f64 / n;
    let spread = triples
        .iter()
        .map(|&t| triple_spread(exemplars, t))
        .sum::<f64>()
        / n;
    let all: Vec<[u32; 3]> = sets
        .iter()
        .flat_map(|s| (0..s.counts.len()).flat_map(move |p| s.of(p).iter().copied()))
        .collect();
    let candidate_spread = all
        .iter()
        .map(|&t| triple_spread(exemplars, t))
        .sum::<f64>()
        / all.len().max(1) as f64;
    TripleConsistency {
        candidate_share: share,
        spread,
        candidate_spread,
    }
}
