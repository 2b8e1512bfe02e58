//! One recipe for a solid texture: everything a volume is made from (the exemplar of each
//! role and how it is fitted and oriented, the feature channel, the candidates' parameters
//! and where they are computed, the schedule, the seed, the relief channel), with one set of
//! defaults. The command line, every bench and a scene's `synthesized` textures only fill a
//! recipe; [`SolidRecipe::load`] is the one exemplar preparation and
//! [`SolidSources::prepare`] the one analysis and candidate step, from which the windowed
//! synthesizer ([`PreparedSolid::synthesizer`], [`PreparedSolid::cube`]) and the lazy one
//! ([`PreparedSolid::lazy`]) are built. Two callers with equal recipes get the same volume.
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use lazysolid_compute::gpu::{Gpu, GpuOptions};
//! use lazysolid_synth::solid::{SolidRecipe, VolumeBox};
//! use lazysolid_synth::DiskCache;
//!
//! let gpu = Gpu::new(&GpuOptions::from_env())?;
//! // The defaults of `lazysolid solid`, with another seed.
//! let recipe = SolidRecipe {
//!     seed: 7,
//!     ..SolidRecipe::new("assets/exemplars/terra.pat")
//! };
//! let sources = recipe.load()?; // fitted and oriented; `sources.fits` says how
//! let cache = DiskCache::user()?;
//! let prepared = sources.prepare(&gpu, Some(&cache), &mut |_, _| {})?;
//! let window = VolumeBox { origin: [0; 3], size: [64; 3] };
//! let cube = prepared.cube(&gpu, window, &mut |_| {})?;
//! assert_eq!(cube.colours.len(), 64 * 64 * 64);
//! # Ok(())
//! # }
//! ```

mod cube;
mod prepared;
mod sources;

pub use cube::SolidCube;
pub use prepared::PreparedSolid;
pub use sources::SolidSources;

use super::roles::ROLES;
use super::{
    solid_jitter_or_default, solid_passes_or_default, CandidateBuilder, CandidateParams,
    Orientation, DEFAULT_SOLID_PARALLEL_LEVELS,
};
use crate::feature::{FeatureMask, DEFAULT_FEATURE_WEIGHT};
use crate::{FitMode, SynthParams, SynthResult};
use std::path::PathBuf;

/// The seed of a recipe that names none (`lazysolid solid --seed`'s default and a scene
/// texture's).
pub const DEFAULT_SOLID_SEED: u32 = 1;

/// How the pyramid's levels are corrected; empty lists and `None` take the solid defaults
/// (`defaults.rs`) for the pyramid the exemplars give, which a recipe cannot know before it
/// loads them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SolidSchedule {
    /// Correction passes: one for every level, or one per level, coarsest first.
    pub passes: Vec<u32>,
    /// Jitter strengths: one for every level, or one per level, coarsest first.
    pub jitter: Vec<f32>,
    /// The correction's current triple always competes (`SynthParams::keep_current`), the
    /// ablation that brings back axis-aligned blocks.
    pub keep_current: bool,
    /// Finest levels corrected in parallel passes (`None`: [`DEFAULT_SOLID_PARALLEL_LEVELS`]).
    pub parallel_levels: Option<u32>,
}

/// Everything a solid texture is made from. [`SolidRecipe::new`] gives the defaults that
/// `lazysolid solid`, the benches and scenes share; a caller changes only the fields its
/// flags or keys name.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidRecipe {
    /// The image playing every role that `roles` leaves `None`.
    pub exemplar: PathBuf,
    /// Images of the roles `E_x`, `E_y`, `E_z` given on their own.
    pub roles: [Option<PathBuf>; ROLES],
    /// How each image is made square with a power-of-two side.
    pub fit: FitMode,
    /// The side the main image is fitted to (`None`: the one `fit` picks); the role images
    /// always take the side the main image got, since every role shares an axis with another.
    pub exemplar_side: Option<u32>,
    /// Whether a role may see its image mirrored (`orientation.rs`).
    pub orientation: Orientation,
    /// Weight of the feature-distance channel, percent of the colour's deviation (0: off).
    pub feature_weight: u32,
    /// Which threshold finds the features.
    pub feature_mask: FeatureMask,
    /// The candidates' construction.
    pub candidates: CandidateParams,
    /// Where the candidates are computed when the cache does not hold them (the same
    /// candidates either way).
    pub builder: CandidateBuilder,
    /// How the levels are corrected.
    pub schedule: SolidSchedule,
    /// Seed of the jitter.
    pub seed: u32,
    /// Whether the lazy state's texels carry the relief channel in alpha (`crate::relief`);
    /// the windowed synthesizer's colours do not depend on it.
    pub relief: bool,
}

impl SolidRecipe {
    /// The defaults, with `exemplar` playing all three roles.
    pub fn new(exemplar: impl Into<PathBuf>) -> SolidRecipe {
        SolidRecipe {
            exemplar: exemplar.into(),
            roles: [None, None, None],
            fit: FitMode::Auto,
            exemplar_side: None,
            orientation: Orientation::Auto,
            feature_weight: DEFAULT_FEATURE_WEIGHT,
            feature_mask: FeatureMask::Auto,
            candidates: CandidateParams::default(),
            builder: CandidateBuilder::Auto,
            schedule: SolidSchedule::default(),
            seed: DEFAULT_SOLID_SEED,
            relief: false,
        }
    }

    /// The synthesizer's parameters for a pyramid of `levels` levels: the schedule's, with
    /// the solid defaults where it names none.
    ///
    /// # Errors
    /// [`crate::SynthError::Parameter`] for lists whose length fits neither one value nor
    /// one per level, and parallel levels past the pyramid.
    pub fn synth_params(&self, levels: u32) -> SynthResult<SynthParams> {
        let s = &self.schedule;
        SynthParams::new(
            levels,
            self.seed,
            &solid_passes_or_default(&s.passes, levels),
            &solid_jitter_or_default(&s.jitter, levels),
        )?
        .with_keep_current(s.keep_current)
        .with_parallel_levels(
            s.parallel_levels
                .unwrap_or(DEFAULT_SOLID_PARALLEL_LEVELS.min(levels)),
        )
    }
}
