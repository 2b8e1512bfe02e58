//! How consistent the synthesized triples are, the cheap checks behind the correction's rule:
//! a triple that is one of the precomputed candidates has three exemplar colours that agree
//! (their crossbars were matched), a triple that upsampling and jitter merely translated in
//! general does not, and the median rule then shows the disagreement as axis-aligned blocks.

use super::candidates::SolidCandidates;
use super::closure::advance_closure;
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
    /// Per role r: the share of voxel pairs adjacent along axis r (the normal of role r's
    /// plane) that hold the same role-r coordinate. Nothing in role r's plane ties a voxel to
    /// its neighbour along the normal, so a share well above what chance gives is extrusion: a
    /// structure of E_r copied unchanged along r, which the slices containing r show as lines
    /// along that axis (an axis-aligned step the blockiness counts).
    pub normal_repeat: [f64; 3],
    /// Per role r: the share of voxel pairs adjacent along an in-plane axis of role r whose
    /// role-r coordinates differ by exactly that one exemplar pixel (coherent copying within
    /// the plane), for comparison with [`TripleConsistency::normal_repeat`].
    pub in_plane_coherence: [f64; 3],
    /// Per role: the finest level's [`advance_closure`], the share of candidates whose set one
    /// step on holds a triple continuing a second role by the same step: how often a step can
    /// keep two roles coherent at once, where [`TripleConsistency::in_plane_coherence`] counts
    /// one role.
    pub advance_closure: [f64; 3],
}

/// The exemplar axes (u, v) of role r's plane as volume axes: role x sees (y, z), role y (x, z),
/// role z (x, y).
const PLANE_AXES: [[usize; 2]; ROLES] = [[1, 2], [0, 2], [0, 1]];

/// [`TripleConsistency::normal_repeat`] and [`TripleConsistency::in_plane_coherence`] of
/// `triples` (a `size` box, x fastest) over an `m`² exemplar.
pub fn extrusion_shares(triples: &[[u32; 3]], size: [u32; 3], m: u32) -> ([f64; 3], [f64; 3]) {
    let [nx, ny, nz] = size.map(|s| s as usize);
    let at = |x: usize, y: usize, z: usize| triples[(z * ny + y) * nx + x];
    let step = [[1usize, 0, 0], [0, 1, 0], [0, 0, 1]];
    let mut normal = [0.0; 3];
    let mut in_plane = [0.0; 3];
    for r in 0..ROLES {
        let (mut same, mut pairs) = (0u64, 0u64);
        let (mut coherent, mut in_pairs) = (0u64, 0u64);
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let p = [x, y, z];
                    let here = at(x, y, z)[r];
                    let next = |axis: usize| {
                        let q = [
                            p[0] + step[axis][0],
                            p[1] + step[axis][1],
                            p[2] + step[axis][2],
                        ];
                        (q[0] < nx && q[1] < ny && q[2] < nz).then(|| at(q[0], q[1], q[2])[r])
                    };
                    if let Some(t) = next(r) {
                        pairs += 1;
                        same += u64::from(t == here);
                    }
                    let (hx, hy) = unpack(here);
                    for (k, &axis) in PLANE_AXES[r].iter().enumerate() {
                        if let Some(t) = next(axis) {
                            in_pairs += 1;
                            let (tx, ty) = unpack(t);
                            let want = if k == 0 {
                                ((hx + 1) % m, hy)
                            } else {
                                (hx, (hy + 1) % m)
                            };
                            coherent += u64::from((tx, ty) == want);
                        }
                    }
                }
            }
        }
        normal[r] = same as f64 / pairs.max(1) as f64;
        in_plane[r] = coherent as f64 / in_pairs.max(1) as f64;
    }
    (normal, in_plane)
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
    let (normal_repeat, in_plane_coherence) = extrusion_shares(&triples, synthesis.window.size, m);
    TripleConsistency {
        candidate_share: share,
        spread,
        candidate_spread,
        normal_repeat,
        in_plane_coherence,
        advance_closure: advance_closure(sets, 1, m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coords::pack;

    #[test]
    fn an_extruded_volume_repeats_along_the_normal_and_a_coherent_one_shifts_in_the_plane() {
        let (n, m) = (6usize, 16u32);
        // Every role's coordinate is the exact copy of its plane position: perfectly coherent in
        // the plane, never repeated along the normal.
        let coherent: Vec<[u32; 3]> = (0..n * n * n)
            .map(|i| {
                let p = [i % n, (i / n) % n, i / (n * n)];
                std::array::from_fn(|r| {
                    let [a, b] = PLANE_AXES[r];
                    pack(p[a] as u32, p[b] as u32)
                })
            })
            .collect();
        let (normal, in_plane) = extrusion_shares(&coherent, [n as u32; 3], m);
        assert_eq!(
            normal, [1.0; 3],
            "a plane position does not change along the normal"
        );
        assert_eq!(in_plane, [1.0; 3]);
        // Offset each slice along the normal: no repeats, still coherent in the plane.
        let shifted: Vec<[u32; 3]> = (0..n * n * n)
            .map(|i| {
                let p = [i % n, (i / n) % n, i / (n * n)];
                std::array::from_fn(|r| {
                    let [a, b] = PLANE_AXES[r];
                    pack((p[a] as u32 + 3 * p[r] as u32) % m, p[b] as u32)
                })
            })
            .collect();
        let (normal, in_plane) = extrusion_shares(&shifted, [n as u32; 3], m);
        assert_eq!(normal, [0.0; 3]);
        assert_eq!(in_plane, [1.0; 3]);
    }
}
