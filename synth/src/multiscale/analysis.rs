//! Analysis of an exemplar graph: per exemplar the Gaussian stack, per distinct depth set of
//! the superexemplar one appearance space over all its stack levels (PCA of their 5×5
//! neighbourhoods pooled, 8D, quantized), the 4-diagonal neighbourhood records, and the
//! k-coherence sets, which range over the correction levels of each stack level (other
//! exemplars' admissible levels included), each member with its colour transfer.
//!
//! Transfer functions are the paper's constant offset (P Eq. 4 and P:173): for a candidate
//! `E^j_l[v]` of `E^i_k[u]`, `b = (1/25) Σ_δ (E^i_k[u + δ h_k] − E^j_l[v + δ h_l])` over the
//! 5×5 neighbourhood, so that `E^j_l + b` looks like `E^i_k`; `b = 0` within one exemplar
//! (P:175). Offsets are stored in 1/[`TRANSFER_ONE`] colour levels, as integers.

use super::graph::{ExemplarGraph, Topology};
use super::superexemplar::{StackLevel, Superexemplar};
use crate::analysis::AnalysisParams;
use crate::appearance::{appearance_distance, sized_appearance, SizedLevel, APPEARANCE_DIMS};
use crate::coherence::{coherence_sets, MAX_POOL};
use crate::coords::{pack, torus_distance};
use crate::error::SynthResult;
use crate::exemplar::Exemplar;
use crate::neighbourhood::{exemplar_neighbourhoods, NEIGHBOURHOOD_DIMS};
use crate::stack::{border, gaussian_stack};
use rayon::prelude::*;

/// Transfer offsets are stored in steps of 1/`TRANSFER_ONE` of a colour level.
pub const TRANSFER_ONE: i32 = 16;

/// One member of a k-coherence set: a texel of a stack level of the same depth set and the
/// transfer that maps its colours to those of the texel whose set it is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Candidate {
    /// Index of the stack level in the depth set's members.
    pub member: u32,
    /// Packed texel coordinate.
    pub coord: u32,
    /// Colour offset, in 1/[`TRANSFER_ONE`] levels.
    pub transfer: [i32; 3],
}

/// One stack level of a depth set.
#[derive(Clone, Debug, PartialEq)]
pub struct MemberAnalysis {
    /// Exemplar.
    pub exemplar: usize,
    /// Stack level.
    pub level: u32,
    /// Spacing `2^(L − level)`.
    pub spacing: u32,
    /// Quantized appearance of every texel, in the depth set's space.
    pub appearance: Vec<[i8; APPEARANCE_DIMS]>,
    /// 4-diagonal neighbourhood record of every texel.
    pub neighbourhoods: Vec<[i8; NEIGHBOURHOOD_DIMS]>,
    /// `k` candidates per texel, row-major.
    pub candidates: Vec<Candidate>,
}

/// One distinct depth set.
#[derive(Clone, Debug, PartialEq)]
pub struct DepthSetAnalysis {
    /// Its stack levels, sorted by (exemplar, level).
    pub members: Vec<MemberAnalysis>,
    /// How a colour offset moves an appearance vector (see `appearance.rs`).
    pub offset_matrix: [[i32; 3]; APPEARANCE_DIMS],
    /// PCA residual variance of the pooled neighbourhoods.
    pub residual_variance: f64,
}

impl DepthSetAnalysis {
    /// The member holding stack level `(exemplar, level)`; a magnified level (beyond the
    /// finest) is its exemplar's finest.
    pub fn member(&self, exemplar: usize, level: u32) -> Option<usize> {
        self.members
            .iter()
            .position(|m| m.exemplar == exemplar && m.level == level)
    }
}

/// What synthesis needs of one exemplar.
#[derive(Clone, Debug, PartialEq)]
pub struct ExemplarInfo {
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Finest level `L`.
    pub finest: u32,
    /// Its Gaussian stack rounded to 8 bits (what the output shows), levels `0..=L`.
    pub stack: Vec<Vec<[u8; 3]>>,
}

/// The analysed graph.
#[derive(Clone, Debug, PartialEq)]
pub struct MultiscaleAnalysis {
    /// The graph's shape.
    pub topology: Topology,
    /// Its superexemplar.
    pub superexemplar: Superexemplar,
    /// Per exemplar.
    pub exemplars: Vec<ExemplarInfo>,
    /// Per distinct depth set (indexed like `superexemplar.sets`).
    pub sets: Vec<DepthSetAnalysis>,
    /// Similarity set size.
    pub k: u32,
}

impl MultiscaleAnalysis {
    /// The analysis of depth `t`.
    pub fn depth(&self, t: u32) -> &DepthSetAnalysis {
        &self.sets[self.superexemplar.set_of(t)]
    }
}

/// The fitted constant offset (in 1/[`TRANSFER_ONE`] levels) that maps the 5×5 neighbourhood
/// of `b` (texel `v` of an image at spacing `hb`) onto that of `a` (texel `u`, spacing `ha`).
pub fn fit_transfer(
    a: (&[[f32; 3]], u32, u32, u32),
    u: (u32, u32),
    b: (&[[f32; 3]], u32, u32, u32),
    v: (u32, u32),
    toroidal: bool,
) -> [i32; 3] {
    let mut sum = [0.0f64; 3];
    for dy in -2i64..=2 {
        for dx in -2i64..=2 {
            let at = |img: (&[[f32; 3]], u32, u32, u32), p: (u32, u32)| {
                let (pixels, w, h, s) = img;
                let x = border(p.0 as i64 + dx * s as i64, w, toroidal);
                let y = border(p.1 as i64 + dy * s as i64, h, toroidal);
                pixels[y * w as usize + x]
            };
            let (ca, cb) = (at(a, u), at(b, v));
            for c in 0..3 {
                sum[c] += ca[c] as f64 - cb[c] as f64;
            }
        }
    }
    sum.map(|s| (s / 25.0 * TRANSFER_ONE as f64).round() as i32)
}

/// Analyses `graph` (see the module docs).
///
/// # Errors
/// [`SynthError::Parameter`](crate::SynthError::Parameter) when `k` or `spread` is out of range.
pub fn analyze_graph(
    graph: &ExemplarGraph,
    params: &AnalysisParams,
) -> SynthResult<MultiscaleAnalysis> {
    analyze_topology(&graph.exemplars, &graph.topology, params)
}

/// [`analyze_graph`] from exemplars and a topology.
///
/// # Errors
/// As [`analyze_graph`].
pub fn analyze_topology(
    exemplars: &[Exemplar],
    topology: &Topology,
    params: &AnalysisParams,
) -> SynthResult<MultiscaleAnalysis> {
    params.check()?;
    let stacks: Vec<Vec<Vec<[f32; 3]>>> = exemplars
        .iter()
        .map(|e| gaussian_stack(e, params.toroidal))
        .collect();
    let superexemplar = topology.superexemplar();
    let sets = superexemplar
        .sets
        .iter()
        .map(|set| analyze_set(exemplars, &stacks, topology, set, params))
        .collect();
    let infos = exemplars
        .iter()
        .zip(&stacks)
        .map(|(e, stack)| ExemplarInfo {
            width: e.width,
            height: e.height,
            finest: e.finest_level(),
            stack: stack
                .iter()
                .enumerate()
                .map(|(l, level)| {
                    if l as u32 == e.finest_level() {
                        e.rgb.clone()
                    } else {
                        level
                            .iter()
                            .map(|c| c.map(|v| v.round().clamp(0.0, 255.0) as u8))
                            .collect()
                    }
                })
                .collect(),
        })
        .collect();
    Ok(MultiscaleAnalysis {
        topology: topology.clone(),
        superexemplar,
        exemplars: infos,
        sets,
        k: params.k,
    })
}

fn analyze_set(
    exemplars: &[Exemplar],
    stacks: &[Vec<Vec<[f32; 3]>>],
    topology: &Topology,
    set: &[StackLevel],
    params: &AnalysisParams,
) -> DepthSetAnalysis {
    let image = |&(i, l): &StackLevel| {
        let e = &exemplars[i];
        (
            stacks[i][l as usize].as_slice(),
            e.width,
            e.height,
            1u32 << (e.finest_level() - l),
        )
    };
    let sized: Vec<SizedLevel> = set
        .iter()
        .map(|s| {
            let (pixels, width, height, spacing) = image(s);
            SizedLevel {
                pixels,
                feature: None,
                width,
                height,
                spacing,
            }
        })
        .collect();
    let shared = sized_appearance(&sized, params.toroidal);
    let k = params.k as usize;
    let members = set
        .iter()
        .enumerate()
        .map(|(m, s)| {
            let (_, w, h, spacing) = image(s);
            let levels = topology.correction_levels(s.0, s.1);
            let targets: Vec<usize> = levels
                .iter()
                .map(|t| set.iter().position(|x| x == t).expect("the set is closed"))
                .collect();
            let candidates: Vec<Candidate> = if targets == [m] {
                coherence_sets(&shared.vectors[m], w, h, params.k, params.spread)
                    .into_iter()
                    .map(|coord| Candidate {
                        member: m as u32,
                        coord,
                        transfer: [0; 3],
                    })
                    .collect()
            } else {
                let pools: Vec<(usize, Vec<(u32, u32)>)> = targets
                    .iter()
                    .map(|&t| {
                        let (_, tw, th, _) = image(&set[t]);
                        (t, pool(tw, th))
                    })
                    .collect();
                let mut out = vec![
                    Candidate {
                        member: 0,
                        coord: 0,
                        transfer: [0; 3]
                    };
                    (w * h) as usize * k
                ];
                out.par_chunks_mut(k).enumerate().for_each(|(i, slots)| {
                    let u = (i as u32 % w, i as u32 / w);
                    let vu = &shared.vectors[m][i];
                    let mut chosen: Vec<(usize, (u32, u32))> = Vec::new();
                    if targets.contains(&m) {
                        chosen.push((m, u));
                    }
                    while chosen.len() < k {
                        let mut best: Option<(u32, usize, (u32, u32))> = None;
                        for (t, p) in &pools {
                            let (_, tw, th, _) = image(&set[*t]);
                            for &v in p {
                                let d = appearance_distance(
                                    vu,
                                    &shared.vectors[*t][(v.1 * tw + v.0) as usize],
                                );
                                if best.is_some_and(|(bd, _, _)| d >= bd) {
                                    continue;
                                }
                                let far = chosen.iter().all(|&(ct, cv)| {
                                    ct != *t || torus_distance(v, cv, tw, th) >= params.spread
                                });
                                if far {
                                    best = Some((d, *t, v));
                                }
                            }
                        }
                        match best {
                            Some((_, t, v)) => chosen.push((t, v)),
                            None => {
                                let first = chosen.first().copied().unwrap_or((targets[0], (0, 0)));
                                chosen.push(first);
                            }
                        }
                    }
                    for (slot, &(t, v)) in slots.iter_mut().zip(&chosen) {
                        let transfer = if set[t].0 == s.0 {
                            [0; 3]
                        } else {
                            fit_transfer(image(s), u, image(&set[t]), v, params.toroidal)
                        };
                        *slot = Candidate {
                            member: t as u32,
                            coord: pack(v.0, v.1),
                            transfer,
                        };
                    }
                });
                out
            };
            MemberAnalysis {
                exemplar: s.0,
                level: s.1,
                spacing,
                neighbourhoods: exemplar_neighbourhoods(&shared.vectors[m], w, h, spacing),
                appearance: shared.vectors[m].clone(),
                candidates,
            }
        })
        .collect();
    DepthSetAnalysis {
        members,
        offset_matrix: shared.offset_matrix,
        residual_variance: shared.residual_variance,
    }
}

/// The brute-force pool of a `w`×`h` level: every pixel, or the regular subgrid of at most
/// [`MAX_POOL`] pixels (as `coherence.rs`).
fn pool(w: u32, h: u32) -> Vec<(u32, u32)> {
    let mut stride = 1;
    while (w.div_ceil(stride) * h.div_ceil(stride)) as usize > MAX_POOL {
        stride += 1;
    }
    (0..h)
        .step_by(stride as usize)
        .flat_map(|y| (0..w).step_by(stride as usize).map(move |x| (x, y)))
        .collect()
}
