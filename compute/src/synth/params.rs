//! Parameters of one synthesis, validated and quantized before either synthesizer sees them.

use super::error::{SynthError, SynthResult};

/// Largest number of correction passes per level.
pub const MAX_PASSES: u32 = 8;

/// Jitter strengths are stored in steps of 1/`JITTER_ONE`, so the jitter is integer arithmetic
/// on both synthesizers.
pub const JITTER_ONE: u32 = 256;

/// A validated synthesis configuration.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SynthParams {
    /// Seed of the jitter hash: different seeds give different (equally deterministic) planes.
    pub seed: u32,
    /// Correction passes per level (the paper uses 2).
    pub passes: u32,
    /// Jitter strength of every level `0..=L`, in 1/[`JITTER_ONE`] steps of the level spacing.
    pub jitter: Vec<u32>,
}

impl SynthParams {
    /// Validates and quantizes: `jitter` holds one strength in 0..=1 for every level (coarsest
    /// first), or a single one used at every level.
    ///
    /// # Errors
    /// [`SynthError::Parameter`] for a strength outside 0..=1, a wrong count of strengths, or
    /// a pass count above [`MAX_PASSES`].
    pub fn new(levels: u32, seed: u32, passes: u32, jitter: &[f32]) -> SynthResult<SynthParams> {
        if passes > MAX_PASSES {
            return Err(SynthError::Parameter {
                name: "passes",
                value: passes.to_string(),
                limit: format!("must be at most {MAX_PASSES}"),
            });
        }
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
        })
    }
}
