//! The multiscale synthesizer's CPU reference: per pixel the state `(exemplar, level,
//! coordinate, cumulative transfer)`, per depth upsampling (the exemplar kept, the transfer
//! interpolated from the four nearest parents), jitter, and correction passes whose matching
//! sees the neighbourhood as displayed (P Eq. 5) and composes the chosen candidate's transfer.
//! Integer arithmetic throughout, mirrored exactly by `glsl/synth/multiscale_*.comp`.

use super::analysis::{DepthSetAnalysis, MultiscaleAnalysis, TRANSFER_ONE};
use crate::appearance::{APPEARANCE_DIMS, OFFSET_MATRIX_BITS};
use crate::coords::{pack, torus_distance, unpack};
use crate::cpu::{offsets, CLASSES};
use crate::error::{SynthError, SynthResult};
use crate::jitter::jitter;
use crate::neighbourhood::{wrap, DIAGONALS, NEIGHBOURHOOD_DIMS, PREDICTIONS};
use crate::params::{default_jitter, default_passes, SynthParams};
use crate::period::{period_reach, PERIOD_TOLERANCE};
use crate::plan::{correction_padding, Region};
use crate::shader_constants;

/// Deepest synthesis level (window origins at depth `t` are absolute positions of a plane
/// `2^t` times finer than the root's level 0).
pub const MAX_DEPTH: u32 = 40;

/// Largest magnitude of an offset's move of one appearance component: keeps every distance
/// inside `u32` (32 · (3 · (2 · 127 + 2 · 512))² < 2³²) whatever the transfers.
pub const MAX_OFFSET_MOVE: i32 = shader_constants::MULTISCALE_MAX_OFFSET_MOVE as i32;

/// Largest magnitude of a cumulative transfer component: one full colour range (255 levels).
/// A larger offset shows the same colours (they clamp), and the bound keeps the offset move
/// inside 32-bit arithmetic (3 · `OFFSET_MATRIX_MAX` · 4080 < 2³¹) on the GPU.
pub const MAX_TRANSFER: i32 = shader_constants::MULTISCALE_MAX_TRANSFER as i32;

/// Level field of a magnified pixel: beyond every finest level.
pub const MAGNIFIED: u32 = shader_constants::MULTISCALE_MAGNIFIED;

/// Fixed-point bits of [`offset_move`].
const OFFSET_MOVE_SHIFT: u32 = shader_constants::MULTISCALE_OFFSET_MOVE_SHIFT;

const _: () = assert!(MAX_TRANSFER == 255 * TRANSFER_ONE);
const _: () = assert!(OFFSET_MOVE_SHIFT == OFFSET_MATRIX_BITS + TRANSFER_ONE.trailing_zeros());

/// One synthesized pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelState {
    /// Packed exemplar coordinate.
    pub coord: u32,
    /// Exemplar in bits 0..8, stack level in bits 8..16 ([`MAGNIFIED`] past a leaf's
    /// finest level).
    pub meta: u32,
    /// Cumulative colour offset, in 1/`TRANSFER_ONE` levels.
    pub transfer: [i32; 3],
}

impl PixelState {
    /// The exemplar.
    pub fn exemplar(&self) -> usize {
        (self.meta & 0xff) as usize
    }

    /// The stack level ([`MAGNIFIED`] for a magnified pixel).
    pub fn level(&self) -> u32 {
        (self.meta >> 8) & 0xff
    }

    /// Whether the pixel is magnified past its leaf exemplar's finest level.
    pub fn magnified(&self) -> bool {
        self.level() == MAGNIFIED
    }
}

/// `meta` of (exemplar, level).
pub fn meta(exemplar: usize, level: u32) -> u32 {
    exemplar as u32 | (level << 8)
}

/// Parameters of one multiscale synthesis, per depth `0..=T`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MultiscaleParams {
    /// Seed of the jitter.
    pub seed: u32,
    /// Correction passes per depth.
    pub passes: Vec<u32>,
    /// Jitter strength per depth, in 1/`JITTER_ONE`.
    pub jitter: Vec<u32>,
    /// Period penalty (see `period.rs`).
    pub period_penalty: u32,
}

impl MultiscaleParams {
    /// Parameters for synthesis down to depth `depth`: one value for every depth or one per
    /// depth; empty lists take the 2D synthesizer's defaults for `depth + 1` levels.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] for out-of-range values.
    pub fn new(
        seed: u32,
        depth: u32,
        passes: &[u32],
        jitter: &[f32],
        period_penalty: u32,
    ) -> SynthResult<MultiscaleParams> {
        if depth > MAX_DEPTH {
            return Err(SynthError::Parameter {
                name: "level",
                value: depth.to_string(),
                limit: format!("must be at most {MAX_DEPTH}"),
            });
        }
        let passes = if passes.is_empty() {
            default_passes(depth + 1)
        } else {
            passes.to_vec()
        };
        let jitter = if jitter.is_empty() {
            default_jitter(depth + 1)
        } else {
            jitter.to_vec()
        };
        // One depth per level of the 2D synthesizer's schedule: the same checks and
        // quantization.
        let p = SynthParams::new(depth + 1, seed, &passes, &jitter)?
            .with_period_penalty(period_penalty)?;
        Ok(MultiscaleParams {
            seed: p.seed,
            passes: p.passes,
            jitter: p.jitter,
            period_penalty: p.period_penalty,
        })
    }

    /// The deepest level.
    pub fn depth(&self) -> u32 {
        self.passes.len() as u32 - 1
    }
}

/// States of one depth over the region computed there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MultiscaleLevel {
    /// Computed region, in this depth's absolute positions.
    pub region: Region,
    /// Row-major states.
    pub states: Vec<PixelState>,
}

impl MultiscaleLevel {
    /// The state at absolute position `p` (which must lie in the region).
    pub fn at(&self, p: [i32; 2]) -> PixelState {
        let r = self.region;
        self.states
            [(p[1] - r.origin[1]) as usize * r.size[0] as usize + (p[0] - r.origin[0]) as usize]
    }

    /// The states of `window` (inside the region), row-major.
    pub fn crop(&self, window: Region) -> Vec<PixelState> {
        let mut out = Vec::with_capacity(window.pixels());
        for y in 0..window.size[1] as i32 {
            for x in 0..window.size[0] as i32 {
                out.push(self.at([window.origin[0] + x, window.origin[1] + y]));
            }
        }
        out
    }
}

/// A synthesized window of depth `T`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MultiscaleSynthesis {
    /// The requested window of depth `T`.
    pub window: Region,
    /// Depths `0..=T` (or only `T`, when the synthesizer was asked not to keep the others).
    pub levels: Vec<MultiscaleLevel>,
}

impl MultiscaleSynthesis {
    /// The window's states.
    pub fn window_states(&self) -> Vec<PixelState> {
        self.levels
            .last()
            .expect("a synthesis has its finest level")
            .crop(self.window)
    }

    /// The window's colours: each pixel's stack texel plus its transfer, rounded and clamped.
    pub fn colours(&self, analysis: &MultiscaleAnalysis) -> Vec<[u8; 3]> {
        self.window_states()
            .iter()
            .map(|s| colour(analysis, s))
            .collect()
    }
}

/// The displayed colour of a state.
pub fn colour(analysis: &MultiscaleAnalysis, s: &PixelState) -> [u8; 3] {
    let e = &analysis.exemplars[s.exemplar()];
    let level = s.level().min(e.finest);
    let (x, y) = unpack(s.coord);
    let c = e.stack[level as usize][(y * e.width + x) as usize];
    std::array::from_fn(|i| {
        let t = (s.transfer[i] + TRANSFER_ONE / 2).div_euclid(TRANSFER_ONE);
        (c[i] as i32 + t).clamp(0, 255) as u8
    })
}

/// The regions to compute at every depth for `window` of the deepest: as the 2D plan, the
/// exact parents grown by one more pixel for the transfer's 4-parent interpolation.
pub fn plan_multiscale(window: Region, passes: &[u32]) -> Vec<Region> {
    let grown = |r: Region, by: u32| Region {
        origin: [r.origin[0] - by as i32, r.origin[1] - by as i32],
        size: [r.size[0] + 2 * by, r.size[1] + 2 * by],
    };
    let parents = |r: Region| {
        let lo = r.origin.map(|o| o.div_euclid(2));
        let hi = [0, 1].map(|a| (r.origin[a] + r.size[a] as i32 - 1).div_euclid(2) + 1);
        Region {
            origin: lo,
            size: [(hi[0] - lo[0]) as u32, (hi[1] - lo[1]) as u32],
        }
    };
    let mut regions = Vec::with_capacity(passes.len());
    let mut exact = window;
    for &p in passes.iter().rev() {
        let computed = grown(exact, correction_padding(p));
        regions.push(computed);
        exact = grown(parents(computed), 1);
    }
    regions.reverse();
    regions
}

/// Checks a window against the limits.
///
/// # Errors
/// [`SynthError::Parameter`] naming the field.
pub fn check_multiscale_window(window: Region) -> SynthResult<()> {
    crate::synthesis::check_window_bounds(window)
}

/// Spacing of a state's level in its exemplar (0 when magnified).
pub fn spacing_of(analysis: &MultiscaleAnalysis, s: &PixelState) -> u32 {
    let finest = analysis.exemplars[s.exemplar()].finest;
    if s.magnified() {
        0
    } else {
        1 << (finest - s.level())
    }
}

/// Bilinear weights (×16) of the 4 nearest parents of a child, nearest first.
const PARENT_WEIGHTS: [i32; 4] = [9, 3, 3, 1];

/// Upsampled (at depth 0: initial) and jittered states of `region` at depth `t`.
pub fn upsample_jitter_multiscale(
    analysis: &MultiscaleAnalysis,
    params: &MultiscaleParams,
    t: u32,
    region: Region,
    parent: Option<&MultiscaleLevel>,
) -> Vec<PixelState> {
    let mut out = Vec::with_capacity(region.pixels());
    for iy in 0..region.size[1] as i32 {
        for ix in 0..region.size[0] as i32 {
            let p = [region.origin[0] + ix, region.origin[1] + iy];
            let mut s = match parent {
                None => {
                    let root = analysis.topology.root;
                    let e = &analysis.exemplars[root];
                    let h = 1u32 << e.finest;
                    PixelState {
                        coord: pack(
                            (p[0].rem_euclid(e.width as i32) as u32 * h) % e.width,
                            (p[1].rem_euclid(e.height as i32) as u32 * h) % e.height,
                        ),
                        meta: meta(root, 0),
                        transfer: [0; 3],
                    }
                }
                Some(parent) => {
                    let q = [p[0].div_euclid(2), p[1].div_euclid(2)];
                    let ps = parent.at(q);
                    let e = &analysis.exemplars[ps.exemplar()];
                    let (x, y) = unpack(ps.coord);
                    let (coord, level) = if !ps.magnified() && ps.level() < e.finest {
                        let h = 1u32 << (e.finest - ps.level() - 1);
                        (
                            pack(
                                (x + h * (p[0] & 1) as u32) % e.width,
                                (y + h * (p[1] & 1) as u32) % e.height,
                            ),
                            ps.level() + 1,
                        )
                    } else {
                        (ps.coord, MAGNIFIED)
                    };
                    let sx = if p[0] & 1 == 1 { 1 } else { -1 };
                    let sy = if p[1] & 1 == 1 { 1 } else { -1 };
                    let near = [
                        ps,
                        parent.at([q[0] + sx, q[1]]),
                        parent.at([q[0], q[1] + sy]),
                        parent.at([q[0] + sx, q[1] + sy]),
                    ];
                    let transfer = std::array::from_fn(|c| {
                        let sum: i32 = near
                            .iter()
                            .zip(PARENT_WEIGHTS)
                            .map(|(n, w)| w * n.transfer[c])
                            .sum();
                        (sum + 8) >> 4
                    });
                    PixelState {
                        coord,
                        meta: meta(ps.exemplar(), level),
                        transfer,
                    }
                }
            };
            if !s.magnified() {
                let e = &analysis.exemplars[s.exemplar()];
                let h = 1u32 << (e.finest - s.level());
                let j = jitter(p[0], p[1], t, params.seed, h, params.jitter[t as usize]);
                let (x, y) = unpack(s.coord);
                s.coord = pack(wrap(x, j[0], e.width), wrap(y, j[1], e.height));
            }
            out.push(s);
        }
    }
    out
}

/// How the offset `b` moves an appearance vector in a depth's space (clamped to
/// ±[`MAX_OFFSET_MOVE`]).
pub fn offset_move(set: &DepthSetAnalysis, b: [i32; 3]) -> [i32; APPEARANCE_DIMS] {
    std::array::from_fn(|d| {
        let m = &set.offset_matrix[d];
        let v: i64 = (0..3).map(|c| m[c] as i64 * b[c] as i64).sum();
        ((v + (1i64 << (OFFSET_MOVE_SHIFT - 1))) >> OFFSET_MOVE_SHIFT)
            .clamp(-MAX_OFFSET_MOVE as i64, MAX_OFFSET_MOVE as i64) as i32
    })
}

/// One correction subpass of depth `t` over the pixels of parity `class`.
pub fn correct_subpass_multiscale(
    analysis: &MultiscaleAnalysis,
    t: u32,
    region: Region,
    states: &mut [PixelState],
    class: [i32; 2],
    period_penalty: u32,
) {
    let set = analysis.depth(t);
    let k = analysis.k as usize;
    let rw = region.size[0] as usize;
    let member = |s: &PixelState| {
        let e = &analysis.exemplars[s.exemplar()];
        set.member(s.exemplar(), s.level().min(e.finest))
    };
    for iy in 1..region.size[1] as i32 - 1 {
        for ix in 1..region.size[0] as i32 - 1 {
            if (region.origin[0] + ix) & 1 != class[0] || (region.origin[1] + iy) & 1 != class[1] {
                continue;
            }
            let mut around = [states[0]; 9];
            for (n, (dx, dy)) in offsets().enumerate() {
                around[n] = states[(iy + dy) as usize * rw + (ix + dx) as usize];
            }
            let current = around[4];
            if current.magnified() || member(&current).is_none() {
                continue;
            }
            // The displayed neighbourhood: per diagonal the sum of 3 predictions, each the
            // predicting pixel's appearance moved by its transfer.
            let moves: [[i32; APPEARANCE_DIMS]; 9] =
                std::array::from_fn(|n| offset_move(set, around[n].transfer));
            let members: [Option<usize>; 9] = std::array::from_fn(|n| member(&around[n]));
            let predict = |n: usize, dx: i32, dy: i32| -> [i32; APPEARANCE_DIMS] {
                let s = &around[n];
                let Some(m) = members[n] else {
                    return [0; APPEARANCE_DIMS];
                };
                let e = &analysis.exemplars[s.exemplar()];
                let h = spacing_of(analysis, s) as i32;
                let (x, y) = unpack(s.coord);
                let (x, y) = (wrap(x, dx * h, e.width), wrap(y, dy * h, e.height));
                let a = set.members[m].appearance[(y * e.width + x) as usize];
                std::array::from_fn(|d| a[d] as i32 + moves[n][d])
            };
            let at = |dx: i32, dy: i32| ((dy + 1) * 3 + dx + 1) as usize;
            let mut sums = [0i32; NEIGHBOURHOOD_DIMS];
            for (j, &(dx, dy)) in DIAGONALS.iter().enumerate() {
                for v in [
                    predict(at(dx, dy), 0, 0),
                    predict(at(dx, 0), 0, dy),
                    predict(at(0, dy), dx, 0),
                ] {
                    for (sum, v) in sums[j * APPEARANCE_DIMS..].iter_mut().zip(v) {
                        *sum += v;
                    }
                }
            }
            // Ranked by (distance, 0 for the current state else 1, meta, coordinate,
            // transfer): the current state survives every tie.
            let mut best: (u32, u32, u32, u32, [i32; 3]) = (
                u32::MAX,
                u32::MAX,
                current.meta,
                current.coord,
                current.transfer,
            );
            for (n, (dx, dy)) in offsets().enumerate() {
                let s = &around[n];
                let Some(m) = members[n] else { continue };
                if s.magnified() {
                    continue;
                }
                let e = &analysis.exemplars[s.exemplar()];
                let h = spacing_of(analysis, s) as i32;
                let (x, y) = unpack(s.coord);
                let base =
                    (wrap(y, -dy * h, e.height) * e.width + wrap(x, -dx * h, e.width)) as usize;
                for c in &set.members[m].candidates[base * k..][..k] {
                    let cm = &set.members[c.member as usize];
                    let ce = &analysis.exemplars[cm.exemplar];
                    let (cx, cy) = unpack(c.coord);
                    let transfer: [i32; 3] = std::array::from_fn(|i| {
                        (s.transfer[i] + c.transfer[i]).clamp(-MAX_TRANSFER, MAX_TRANSFER)
                    });
                    let mv = offset_move(set, transfer);
                    let record = &cm.neighbourhoods[(cy * ce.width + cx) as usize];
                    let mut d = 0u32;
                    for (i, (&sum, &r)) in sums.iter().zip(record.iter()).enumerate() {
                        let diff = sum - PREDICTIONS * (r as i32 + mv[i % APPEARANCE_DIMS]);
                        d = d.wrapping_add((diff * diff) as u32);
                    }
                    let cmeta = meta(cm.exemplar, cm.level);
                    if period_penalty != 0 {
                        let reach = period_reach(cm.spacing, ce.width, ce.height);
                        if reach != [0, 0]
                            && spans_period_multiscale(analysis, c.coord, cmeta, &around, reach)
                        {
                            d = d.wrapping_add(period_penalty);
                        }
                    }
                    let is_current = cmeta == current.meta
                        && c.coord == current.coord
                        && transfer == current.transfer;
                    let key = (d, (!is_current) as u32, cmeta, c.coord, transfer);
                    if key < best {
                        best = key;
                    }
                }
            }
            states[iy as usize * rw + ix as usize] = PixelState {
                coord: best.3,
                meta: best.2,
                transfer: best.4,
            };
        }
    }
}

/// `spans_period` of `period.rs` for the multiscale state: a neighbour continues the
/// candidate's patch when it is at the same stack level and its coordinate, moved back by its
/// offset, lies within the tolerance.
pub fn spans_period_multiscale(
    analysis: &MultiscaleAnalysis,
    c: u32,
    cmeta: u32,
    around: &[PixelState; 9],
    reach: [u32; 2],
) -> bool {
    let (mut lo, mut hi) = ([0i32; 2], [0i32; 2]);
    for (n, s) in around.iter().enumerate() {
        if n == 4 || s.meta != cmeta {
            continue;
        }
        let (dx, dy) = (n as i32 % 3 - 1, n as i32 / 3 - 1);
        let e = &analysis.exemplars[s.exemplar()];
        let h = spacing_of(analysis, s) as i32;
        let (x, y) = unpack(s.coord);
        let continued = (wrap(x, -dx * h, e.width), wrap(y, -dy * h, e.height));
        if torus_distance(unpack(c), continued, e.width, e.height) <= PERIOD_TOLERANCE {
            for (a, d) in [dx, dy].into_iter().enumerate() {
                lo[a] = lo[a].min(d);
                hi[a] = hi[a].max(d);
            }
        }
    }
    (0..2).any(|a| reach[a] != 0 && (hi[a] - lo[a]) as u32 >= reach[a])
}

/// Synthesizes `window` of depth `params.depth()` on the CPU, keeping every depth.
///
/// # Errors
/// A window out of range.
pub fn synthesize_multiscale_cpu(
    analysis: &MultiscaleAnalysis,
    params: &MultiscaleParams,
    window: Region,
) -> SynthResult<MultiscaleSynthesis> {
    check_multiscale_window(window)?;
    let regions = plan_multiscale(window, &params.passes);
    let mut levels: Vec<MultiscaleLevel> = Vec::with_capacity(regions.len());
    for (t, &region) in regions.iter().enumerate() {
        let t = t as u32;
        let mut states = upsample_jitter_multiscale(analysis, params, t, region, levels.last());
        for _ in 0..params.passes[t as usize] {
            for class in CLASSES {
                correct_subpass_multiscale(
                    analysis,
                    t,
                    region,
                    &mut states,
                    class,
                    params.period_penalty,
                );
            }
        }
        levels.push(MultiscaleLevel { region, states });
    }
    Ok(MultiscaleSynthesis { window, levels })
}
