//! Admissible candidates and the superexemplar (Han et al. 2008, §3.2 and appendix; thesis
//! T:946–991, T:1302–1368).
//!
//! Level numbering: stack level `k` of exemplar `i` runs from 0 (coarsest, spacing
//! `h = 2^L_i`) to `L_i` (the exemplar itself, spacing 1), as in the 2D synthesizer and the
//! notes (§1.1). A synthesis pixel at depth `t` has the physical size of `2^(L_root − t)` root
//! texels.
//!
//! `A(E^i_k) = { E^j_l | (i, j, r) ∈ E, l = k − r + (L_j − L_i), 0 ≤ l < L_j }`, the implicit
//! `r = 0` self-loop included. With all exemplars of the same size (the paper's assumption)
//! `l = k − r`; the `L_j − L_i` term keeps the physical scale equal for exemplars of different
//! sizes (a pixel `2^(L_i − k)` texels of `E^i` wide is `2^(L_i − k + r)` texels of `E^j`).
//! Finest levels are never admissible (the paper's rule), so the correction moves every pixel
//! off a finest level where it can.
//!
//! **Leaf policy** (the sources leave it open, notes §5.7): when `A(E^i_L)` is empty (no edge
//! with `r ≥ 1` leaves `i`), the finest level stays admissible for itself —
//! [`Topology::correction_levels`] is `{E^i_L}` — which is exactly the 2D synthesizer's finest
//! level. One level deeper such a pixel is **magnified**: its children keep its texel (no
//! offset, no jitter) and it is no longer corrected; its colour and transfer still follow.
//!
//! **Superexemplar**: the set `D_t` of stack levels that can appear at depth `t` is the
//! closure under the correction levels of the upsampled set `D_(t−1)` (every `(i, k)` to
//! `(i, k + 1)`, a leaf's finest level to itself); `D_0` is the closure of the root's
//! level 0. Only distinct sets are analysed: once `D_t` equals an earlier `D_s` the sequence
//! repeats with period `t − s`, so loops stay finite.

use super::graph::Topology;
use std::collections::{BTreeSet, HashMap};

/// A stack level: (exemplar, level).
pub type StackLevel = (usize, u32);

impl Topology {
    /// The stack level `l` of `j` with the physical scale of level `k` of `i` across an edge of
    /// relation `r`, when it exists (`0 ≤ l ≤ L_j`).
    fn across(&self, i: usize, k: u32, j: usize, r: u32) -> Option<u32> {
        let l = k as i64 - r as i64 + self.finest[j] as i64 - self.finest[i] as i64;
        (0..=self.finest[j] as i64).contains(&l).then_some(l as u32)
    }

    /// `A(E^i_k)` by the paper's rule (finest levels excluded), sorted.
    pub fn admissible(&self, i: usize, k: u32) -> Vec<StackLevel> {
        let mut out = BTreeSet::new();
        let self_loop = crate::multiscale::graph::GraphEdge {
            source: i,
            destination: i,
            r: 0,
        };
        for e in std::iter::once(&self_loop).chain(self.edges.iter().filter(|e| e.source == i)) {
            if let Some(l) = self.across(i, k, e.destination, e.r) {
                if l < self.finest[e.destination] {
                    out.insert((e.destination, l));
                }
            }
        }
        out.into_iter().collect()
    }

    /// Whether `i` is a leaf: its finest level has no admissible candidate.
    pub fn is_leaf(&self, i: usize) -> bool {
        self.admissible(i, self.finest[i]).is_empty()
    }

    /// The levels the correction of a pixel at `(i, k)` chooses from: `A(E^i_k)`, or under the
    /// leaf policy `{E^i_L}` for a leaf's finest level.
    pub fn correction_levels(&self, i: usize, k: u32) -> Vec<StackLevel> {
        let a = self.admissible(i, k);
        if a.is_empty() && k == self.finest[i] {
            vec![(i, k)]
        } else {
            a
        }
    }

    /// `set` closed under [`Topology::correction_levels`].
    fn closure(&self, set: BTreeSet<StackLevel>) -> BTreeSet<StackLevel> {
        let mut out = set.clone();
        let mut todo: Vec<StackLevel> = set.into_iter().collect();
        while let Some((i, k)) = todo.pop() {
            for s in self.correction_levels(i, k) {
                if out.insert(s) {
                    todo.push(s);
                }
            }
        }
        out
    }

    /// The upsampled set: `(i, k + 1)`, a leaf's finest level to itself (magnified); a
    /// non-leaf's finest level has no successor (the correction always moves it away).
    fn upsampled(&self, set: &BTreeSet<StackLevel>) -> BTreeSet<StackLevel> {
        set.iter()
            .filter_map(|&(i, k)| {
                if k < self.finest[i] {
                    Some((i, k + 1))
                } else if self.is_leaf(i) {
                    Some((i, k))
                } else {
                    None
                }
            })
            .collect()
    }

    /// The superexemplar's distinct depth sets.
    pub fn superexemplar(&self) -> Superexemplar {
        let mut sets: Vec<Vec<StackLevel>> = Vec::new();
        let mut index: HashMap<Vec<StackLevel>, usize> = HashMap::new();
        let mut sequence = Vec::new();
        let mut current = self.closure(BTreeSet::from([(self.root, 0)]));
        loop {
            let key: Vec<StackLevel> = current.iter().copied().collect();
            if let Some(&s) = index.get(&key) {
                let loop_start = sequence.iter().position(|&x| x == s).expect("seen");
                return Superexemplar {
                    sets,
                    sequence,
                    loop_start,
                };
            }
            index.insert(key.clone(), sets.len());
            sequence.push(sets.len());
            sets.push(key);
            current = self.closure(self.upsampled(&current));
        }
    }
}

/// The distinct depth sets of the superexemplar and which one each depth uses.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Superexemplar {
    /// Distinct sets of stack levels, sorted, in order of first appearance.
    pub sets: Vec<Vec<StackLevel>>,
    /// Set of depth `t` for `t < sequence.len()`.
    pub sequence: Vec<usize>,
    /// Depths from `loop_start` on repeat with period `sequence.len() − loop_start`.
    pub loop_start: usize,
}

impl Superexemplar {
    /// Index of the set of depth `t`.
    pub fn set_of(&self, t: u32) -> usize {
        let t = t as usize;
        if t < self.sequence.len() {
            self.sequence[t]
        } else {
            let period = self.sequence.len() - self.loop_start;
            self.sequence[self.loop_start + (t - self.loop_start) % period]
        }
    }

    /// The stack levels of depth `t`.
    pub fn depth(&self, t: u32) -> &[StackLevel] {
        &self.sets[self.set_of(t)]
    }
}
