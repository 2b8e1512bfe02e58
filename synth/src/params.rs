//! Parameters of one synthesis, validated and quantized before either synthesizer sees them.

use super::error::{SynthError, SynthResult};

/// Largest number of correction passes per level.
pub const MAX_PASSES: u32 = 8;

/// Jitter strengths are stored in steps of 1/`JITTER_ONE`, so the jitter is integer arithmetic
/// on both synthesizers.
pub const JITTER_ONE: u32 = 256;

/// Default correction passes of every level but the finest. More passes at the coarse levels
/// lower the neighbourhood energy most (they fix the layout that every finer level inherits),
/// and a coarse level is small, so they cost little; see docs/synthesis.md for the measurements.
pub const DEFAULT_PASSES: u32 = 4;

/// Default correction passes of the finest level, the largest region: each pass there costs
/// about as much as all coarser levels together, and a third pass lowers the energy by only
/// 1–2 % while taking 512² from a 64² exemplar from about 350 to about 440 ms on lavapipe,
/// too close to the 0.5 s budget (docs/synthesis.md, "Jitter schedule").
pub const DEFAULT_FINEST_PASSES: u32 = 2;

/// Default jitter strengths of the coarsest levels, coarsest first; finer levels take
/// [`DEFAULT_FINE_JITTER`]. The coarse levels set the layout every finer level inherits, so
/// strong jitter there breaks the exemplar's period into differently shifted copies; at the
/// fine levels jitter mostly cuts seams that the correction then has to repair, so it is weak
/// there (at spacings 1 and 2 a strength of 0.2 rounds to no offset at all). The full strength
/// at the coarsest level (each level-0 block a randomly shifted copy), with the period
/// penalty, takes the mean period repetition at 256² from 0.26–0.74 to 0.10–0.36 on nine
/// exemplars, at 17–80 % more neighbourhood energy (docs/synthesis.md, "Repetition bound").
pub const DEFAULT_COARSE_JITTER: [f32; 4] = [1.0, 0.8, 0.6, 0.4];

/// Default jitter strength of the levels finer than those of [`DEFAULT_COARSE_JITTER`].
pub const DEFAULT_FINE_JITTER: f32 = 0.2;

/// Largest period penalty: above every correction distance (at most 32 · (2 · 3 · 127)² ≈
/// 1.9·10⁷ < 2²⁵), so the largest penalty ranks a penalized candidate behind every other,
/// and distance plus penalty stays inside `u32`.
pub const MAX_PERIOD_PENALTY: u32 = 1 << 25;

/// Default period penalty (`period.rs`): the largest, so that a candidate whose coherent patch
/// would span an exemplar period ranks behind every other. Alone it lowered the repetition on
/// four of five exemplars but not under 0.35; with the stronger coarse jitter above it keeps
/// the layouts from healing back into the tiling (docs/synthesis.md, "Repetition bound").
pub const DEFAULT_PERIOD_PENALTY: u32 = MAX_PERIOD_PENALTY;

/// The multiscale synthesizer's default jitter strengths for a pyramid of `levels` levels,
/// coarsest first (and the 2D one's before the fine levels' jitter was dropped).
pub fn default_jitter(levels: u32) -> Vec<f32> {
    jitter_schedule(levels, &DEFAULT_COARSE_JITTER, DEFAULT_FINE_JITTER)
}

/// The 2D synthesizer's default jitter strengths, coarsest first: [`DEFAULT_COARSE_JITTER`] at
/// the four coarsest levels, none below. The coarse levels set the layout; below them the
/// jitter (0.2 of the spacing: ±2 px at spacing 8, ±1 px on a minority of pixels at spacing 4,
/// nothing finer) breaks no layout, but every jittered pixel cuts a seam that the passes only
/// partly repair. Measured on fifteen exemplars at 512², seed 3 (docs/synthesis.md, "Fine
/// jitter"): neighbourhood energy 6–43 % lower on all fifteen, calibrated SWD ratio within
/// ±0.04, period and layout repetition unchanged.
pub fn default_plane_jitter(levels: u32) -> Vec<f32> {
    jitter_schedule(levels, &DEFAULT_COARSE_JITTER, 0.0)
}

/// `levels` jitter strengths, coarsest first: `coarse` at the coarsest levels, `fine` at every
/// level below them (the shape of the 2D and the solid defaults).
pub fn jitter_schedule(levels: u32, coarse: &[f32], fine: f32) -> Vec<f32> {
    (0..levels as usize)
        .map(|l| coarse.get(l).copied().unwrap_or(fine))
        .collect()
}

/// `given` per-level values, or `default` when none were given (how the command line reads
/// an absent `--passes` or `--jitter`).
pub fn given_or<T: Clone>(given: &[T], default: impl FnOnce() -> Vec<T>) -> Vec<T> {
    if given.is_empty() {
        default()
    } else {
        given.to_vec()
    }
}

/// `given` jitter strengths, or the 2D defaults for `levels` levels when none were given.
pub fn jitter_or_default(given: &[f32], levels: u32) -> Vec<f32> {
    given_or(given, || default_plane_jitter(levels))
}

/// `given` pass counts, or the 2D defaults for `levels` levels over an exemplar whose smaller
/// side is `exemplar_side` when none were given (how the command line reads an absent
/// `--passes`).
pub fn passes_or_default(given: &[u32], levels: u32, exemplar_side: u32) -> Vec<u32> {
    given_or(given, || default_passes_for(levels, exemplar_side))
}

/// Correction passes at every level (the finest [`DEFAULT_FINEST_PASSES`], the others
/// [`DEFAULT_PASSES`]): the multiscale synthesizer's default, and the 2D one's before the
/// layout levels were left uncorrected.
pub fn default_passes(levels: u32) -> Vec<u32> {
    pass_schedule(levels, DEFAULT_PASSES, DEFAULT_FINEST_PASSES)
}

/// The 2D synthesizer's default pass counts, coarsest first: as [`default_passes`], except
/// that a level whose 5×5 neighbourhood spans a whole exemplar period or more (`4 h ≥ side`,
/// with `h` the level spacing) is not corrected. At such a level every neighbourhood wraps
/// around the exemplar, the best match of a jittered block is the exemplar's own layout, and
/// the correction heals the jitter back into a near-tiling that every finer level inherits:
/// a grid of the exemplar's large structures, visible at a glance at 512². Leaving these levels
/// uncorrected removes the grid at nearly the same calibrated SWD, while the neighbourhood
/// energy, which rewards copying, rises (docs/synthesis.md, "Layout levels: left uncorrected";
/// the figures in docs/log/synthesis.md, "Layout levels").
pub fn default_passes_for(levels: u32, exemplar_side: u32) -> Vec<u32> {
    let finest = levels.saturating_sub(1);
    let mut passes = default_passes(levels);
    for (l, p) in passes.iter_mut().enumerate().take(finest as usize) {
        if layout_level(finest - l as u32, exemplar_side) {
            *p = 0;
        }
    }
    passes
}

/// Whether a level of spacing `2^octave` is a layout level of an exemplar whose smaller side
/// is `exemplar_side`: its 5×5 neighbourhood (`±2h`) spans the whole period.
pub fn layout_level(octave: u32, exemplar_side: u32) -> bool {
    4u64 << octave >= u64::from(exemplar_side)
}

/// `levels` pass counts, coarsest first: `coarse` at every level but the finest, `finest`
/// there (the shape of the 2D and the solid defaults).
pub fn pass_schedule(levels: u32, coarse: u32, finest: u32) -> Vec<u32> {
    (0..levels)
        .map(|l| if l + 1 == levels { finest } else { coarse })
        .collect()
}

/// A validated synthesis configuration.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SynthParams {
    /// Seed of the jitter hash: different seeds give different (equally deterministic) planes.
    pub seed: u32,
    /// Correction passes of every level `0..=L` (the paper uses 2 everywhere; coarse levels
    /// are cheap, so more passes there buy quality at little cost).
    pub passes: Vec<u32>,
    /// Jitter strength of every level `0..=L`, in 1/[`JITTER_ONE`] steps of the level spacing.
    pub jitter: Vec<u32>,
    /// Added to the distance of a candidate whose coherent patch would span an exemplar period
    /// (`period.rs`); 0 turns the test off.
    pub period_penalty: u32,
    /// Solid synthesis only: a voxel's current triple competes in the correction even when it
    /// is none of the gathered candidates. Off by default: upsampling and jitter only translate
    /// a parent's triple, so inside a block it keeps a near-zero distance and wins, although
    /// its three exemplar colours disagree and the median shows them as axis-aligned
    /// rectangles (`docs/solid.md`, "Correction"). On is the `keep current` ablation of
    /// `bench solid`, which shows those rectangles.
    pub keep_current: bool,
    /// Solid synthesis only: how many of the finest levels correct every voxel at once per
    /// pass (Jacobi) instead of in eight ordered parity subpasses (`solid/schedule.rs`). A
    /// parallel finest level makes lazy synthesis correct exactly the requested voxels.
    pub parallel_levels: u32,
}

impl SynthParams {
    /// Validates and quantizes: `passes` and `jitter` each hold one value for every level
    /// (coarsest first), or a single one used at every level; jitter strengths lie in 0..=1.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] for a strength outside 0..=1, a wrong count of strengths or
    /// pass counts, or a pass count above [`MAX_PASSES`].
    pub fn new(levels: u32, seed: u32, passes: &[u32], jitter: &[f32]) -> SynthResult<SynthParams> {
        if passes.len() != 1 && passes.len() != levels as usize {
            return Err(SynthError::Parameter {
                name: "passes",
                value: format!("{} counts", passes.len()),
                limit: format!("give one count or one per level ({levels} levels)"),
            });
        }
        if let Some(bad) = passes.iter().find(|&&p| p > MAX_PASSES) {
            return Err(SynthError::Parameter {
                name: "passes",
                value: bad.to_string(),
                limit: format!("must be at most {MAX_PASSES}"),
            });
        }
        let passes = (0..levels as usize)
            .map(|l| passes[l.min(passes.len() - 1)])
            .collect();
        if jitter.len() != 1 && jitter.len() != levels as usize {
            return Err(SynthError::Parameter {
                name: "jitter",
                value: format!("{} strengths", jitter.len()),
                limit: format!("give one strength or one per level ({levels} levels)"),
            });
        }
        if let Some(bad) = jitter.iter().find(|r| !(0.0..=1.0).contains(*r)) {
            return Err(SynthError::Parameter {
                name: "jitter",
                value: bad.to_string(),
                limit: "each strength must lie in 0..=1".into(),
            });
        }
        let q = |r: f32| (r * JITTER_ONE as f32).round() as u32;
        let jitter = (0..levels as usize)
            .map(|l| q(jitter[l.min(jitter.len() - 1)]))
            .collect();
        Ok(SynthParams {
            seed,
            passes,
            jitter,
            period_penalty: DEFAULT_PERIOD_PENALTY,
            keep_current: false,
            parallel_levels: 0,
        })
    }

    /// The same parameters with another period penalty.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] for a penalty above [`MAX_PERIOD_PENALTY`].
    pub fn with_period_penalty(self, penalty: u32) -> SynthResult<SynthParams> {
        if penalty > MAX_PERIOD_PENALTY {
            return Err(SynthError::Parameter {
                name: "period penalty",
                value: penalty.to_string(),
                limit: format!("must be at most {MAX_PERIOD_PENALTY}"),
            });
        }
        Ok(SynthParams {
            period_penalty: penalty,
            ..self
        })
    }

    /// The same parameters with the solid correction's current triple always competing (or
    /// not): see [`SynthParams::keep_current`].
    pub fn with_keep_current(self, keep_current: bool) -> SynthParams {
        SynthParams {
            keep_current,
            ..self
        }
    }

    /// The same parameters with the `levels` finest levels corrected in parallel passes: see
    /// [`SynthParams::parallel_levels`].
    ///
    /// # Errors
    /// [`SynthError::Parameter`] for more levels than the pyramid has.
    pub fn with_parallel_levels(self, levels: u32) -> SynthResult<SynthParams> {
        if levels as usize > self.passes.len() {
            return Err(SynthError::Parameter {
                name: "parallel levels",
                value: levels.to_string(),
                limit: format!("the pyramid has {} levels", self.passes.len()),
            });
        }
        Ok(SynthParams {
            parallel_levels: levels,
            ..self
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_levels_are_those_whose_neighbourhood_spans_the_period() {
        // 64²: spacings 64, 32, 16 span the period (4h ≥ 64); 8 does not.
        assert_eq!(default_passes_for(7, 64), vec![0, 0, 0, 4, 4, 4, 2]);
        // 144²: spacings 128 and 64 (4 · 32 = 128 < 144).
        assert_eq!(default_passes_for(8, 144), vec![0, 0, 4, 4, 4, 4, 4, 2]);
        // The smallest exemplar keeps its two finest levels corrected.
        assert_eq!(default_passes_for(5, 16), vec![0, 0, 0, 4, 2]);
        // The multiscale schedule corrects every level.
        assert_eq!(default_passes(5), vec![4, 4, 4, 4, 2]);
    }

    #[test]
    fn plane_jitter_stops_below_the_four_coarsest_levels() {
        assert_eq!(
            default_plane_jitter(8),
            vec![1.0, 0.8, 0.6, 0.4, 0.0, 0.0, 0.0, 0.0]
        );
        assert_eq!(default_plane_jitter(3), vec![1.0, 0.8, 0.6]);
        // The multiscale schedule keeps 0.2 below them.
        assert_eq!(default_jitter(6)[4..], [0.2, 0.2]);
    }
}
