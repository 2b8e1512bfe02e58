//! Default correction passes of the volume synthesizer.
//!
//! Two passes at the coarse levels (the thesis uses 2) correct the layout where it is cheap;
//! the finest level, most of the voxels and the cost of lazy synthesis around a surface, gets
//! one. The 2D defaults (4 coarse, 2 finest) buy a somewhat lower neighbourhood energy, and a
//! worse histogram, for several times the voxel updates, with slices that look alike
//! (`docs/log/solid.md`, "Volume synthesizer", "Default correction passes").

use crate::params::{given_or, jitter_schedule, pass_schedule};

/// Jitter strengths of the volume synthesizer's coarsest levels, coarsest first; finer levels
/// take [`DEFAULT_SOLID_FINE_JITTER`]. The 2D synthesizer's previous schedule: the solid keeps
/// it because its period repetition already stays at or below 0.28 on every bench exemplar
/// (the three roles' crossbar constraint breaks the tiling that one image heals into), and a
/// stronger coarse jitter would only cut more seams for the single finest pass to repair.
pub const DEFAULT_SOLID_COARSE_JITTER: [f32; 4] = [0.6, 0.5, 0.4, 0.3];

/// Jitter strength of the levels finer than those of [`DEFAULT_SOLID_COARSE_JITTER`].
pub const DEFAULT_SOLID_FINE_JITTER: f32 = 0.2;

/// The default jitter strengths of a volume pyramid of `levels` levels, coarsest first.
pub fn default_solid_jitter(levels: u32) -> Vec<f32> {
    jitter_schedule(
        levels,
        &DEFAULT_SOLID_COARSE_JITTER,
        DEFAULT_SOLID_FINE_JITTER,
    )
}

/// `given` jitter strengths, or the solid defaults for `levels` levels when none were given.
pub fn solid_jitter_or_default(given: &[f32], levels: u32) -> Vec<f32> {
    given_or(given, || default_solid_jitter(levels))
}

/// Correction passes of every level but the finest.
pub const DEFAULT_SOLID_PASSES: u32 = 2;

/// Correction passes of the finest level.
pub const DEFAULT_SOLID_FINEST_PASSES: u32 = 1;

/// Finest levels corrected in parallel passes (`schedule.rs`); the ordered subpasses'
/// dependency chain is what made lazy synthesis compute several times the requested voxels
/// at the finest level (`docs/lazy.md`, "Dependency chains").
pub const DEFAULT_SOLID_PARALLEL_LEVELS: u32 = 1;

/// The default pass counts of a volume pyramid of `levels` levels, coarsest first.
pub fn default_solid_passes(levels: u32) -> Vec<u32> {
    pass_schedule(levels, DEFAULT_SOLID_PASSES, DEFAULT_SOLID_FINEST_PASSES)
}

/// `given` pass counts, or the solid defaults for `levels` levels when none were given (how
/// the command line reads an absent `--passes`).
pub fn solid_passes_or_default(given: &[u32], levels: u32) -> Vec<u32> {
    given_or(given, || default_solid_passes(levels))
}
