//! The synthesis tuning flags, defined once: every command that synthesizes flattens these
//! groups in, so a flag has one name, one parser and one help text wherever it appears, under
//! the help heading "Synthesis tuning".

use clap::{Args, ValueEnum};
use lazysolid_synth::feature::FeatureMask;
use lazysolid_synth::solid::Orientation;
use lazysolid_synth::solid::SolidSchedule;
use lazysolid_synth::{DEFAULT_COHERENCE_K, DEFAULT_COHERENCE_SPREAD, DEFAULT_PERIOD_PENALTY};

/// The per-level schedule of the pyramid synthesis: how strongly each level is jittered and
/// how often it is corrected. Empty lists mean the synthesizer's own defaults.
#[derive(Args, Clone, Debug, Default)]
#[command(next_help_heading = "Synthesis tuning")]
pub struct Schedule {
    /// Jitter strength in 0..=1, one for all levels or a comma-separated list, coarsest first
    /// [default: 2D 1.0, 0.8, 0.6, 0.4 at the four coarsest levels, 0 below; multiscale the same
    /// with 0.2 below; solid 0.6, 0.5, 0.4, 0.3, then 0.2].
    #[arg(long, value_delimiter = ',')]
    pub jitter: Vec<f32>,
    /// Correction passes, one for all levels or a comma-separated list, coarsest first
    /// [default: 2D 0 at the levels whose 5x5 neighbourhood spans the exemplar (spacing at
    /// least a quarter of its side: correcting them lays the exemplar out as a grid), 4 at the
    /// others, 2 at the finest; multiscale 4 per level, 2 at the finest; solid 2 per level, 1
    /// at the finest]. Each solid pass pads every level's box by up to 5, 3 and 2 voxels a side along
    /// x, y and z, so fewer passes make a small run possible on a slow device.
    #[arg(long, value_delimiter = ',')]
    pub passes: Vec<u32>,
}

impl Schedule {
    /// The solid recipe's schedule these flags and `order` give (empty lists: the solid
    /// defaults).
    pub fn solid(&self, order: &SolidOrder) -> SolidSchedule {
        SolidSchedule {
            passes: self.passes.clone(),
            jitter: self.jitter.clone(),
            keep_current: false,
            parallel_levels: order.parallel_levels,
        }
    }
}

/// The 2D correction's candidate sets: their size and spread, and the period penalty that
/// keeps a coherent patch from spanning an exemplar period.
#[derive(Args, Clone, Debug)]
#[command(next_help_heading = "Synthesis tuning")]
pub struct Coherence {
    /// Added to the distance of a candidate whose coherent patch would span an exemplar
    /// period (0 turns the test off; the default ranks such a candidate behind every other).
    #[arg(long, default_value_t = DEFAULT_PERIOD_PENALTY)]
    pub period_penalty: u32,
    /// Size of the k-coherence similarity sets.
    #[arg(short, long, default_value_t = DEFAULT_COHERENCE_K)]
    pub k: u32,
    /// Smallest distance in pixels between members of a similarity set (at the same stack
    /// level, in multiscale).
    #[arg(long, default_value_t = DEFAULT_COHERENCE_SPREAD)]
    pub spread: u32,
}

/// The feature-distance channel of the appearance space.
#[derive(Args, Clone, Debug)]
#[command(next_help_heading = "Synthesis tuning")]
pub struct Features {
    /// Weight of the feature-distance channel in the appearance space, in percent of the
    /// colour's standard deviation, 0 to 400 (0: colour only): a signed distance to the
    /// exemplar's cracks, veins or outlines, found automatically (docs/synthesis.md,
    /// docs/solid.md)
    #[arg(long, default_value_t = lazysolid_synth::feature::DEFAULT_FEATURE_WEIGHT)]
    pub feature_weight: u32,
    /// Which threshold of the local detail finds the features (docs/synthesis.md, "Feature
    /// distance"; the run prints which one was taken)
    #[arg(long, value_enum, default_value_t = Mask::Auto)]
    pub feature_mask: Mask,
}

/// `--feature-mask`: which threshold finds an exemplar's features.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Mask {
    /// Otsu's split, or the minimum-error one where its class is a connected structure that
    /// reaches clearly farther (or Otsu's split is speckle)
    #[default]
    Auto,
    /// Otsu's split always
    Otsu,
    /// The minimum-error (Kittler-Illingworth) split always
    MinimumError,
}

impl From<Mask> for FeatureMask {
    fn from(m: Mask) -> FeatureMask {
        match m {
            Mask::Auto => FeatureMask::Auto,
            Mask::Otsu => FeatureMask::Otsu,
            Mask::MinimumError => FeatureMask::MinimumError,
        }
    }
}

/// `--orientation`: whether a role may see its exemplar mirrored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum RoleOrientation {
    /// Mirror one role's image left-right where the three roles' diagonal preferences have
    /// no consistent 3D structure (a negative diagonal correlation in all three, each at least
    /// 0.05 in size; the run prints what it did)
    #[default]
    Auto,
    /// Every role sees its image as given
    Keep,
    /// As auto, whatever the size of the correlations
    Mirror,
}

impl From<RoleOrientation> for Orientation {
    fn from(o: RoleOrientation) -> Orientation {
        match o {
            RoleOrientation::Auto => Orientation::Auto,
            RoleOrientation::Keep => Orientation::Keep,
            RoleOrientation::Mirror => Orientation::Mirror,
        }
    }
}

/// How the volume synthesizer's finest levels run their correction passes.
#[derive(Args, Clone, Debug, Default)]
#[command(next_help_heading = "Synthesis tuning")]
pub struct SolidOrder {
    /// Finest levels whose correction passes update every voxel at once from the previous
    /// pass (Jacobi) instead of in eight ordered parity subpasses: lazy synthesis then
    /// corrects only the requested voxels at those levels (docs/lazy.md)
    /// [default: lazysolid_synth's DEFAULT_SOLID_PARALLEL_LEVELS].
    #[arg(long, value_name = "N")]
    pub parallel_levels: Option<u32>,
}

/// Most pixels the neighbourhood energy evaluates: one flag for every command that reports
/// the energy, so a 2D window and a solid's slices are scored on the same footing.
pub const DEFAULT_ENERGY_SAMPLES: usize = 4096;

/// How many pixels the neighbourhood energy (the quality figure of every synthesis) evaluates.
#[derive(Args, Clone, Debug)]
pub struct Energy {
    /// Most pixels of each output the neighbourhood energy evaluates (a 2D window, each slice of
    /// a solid, each quality window of a multiscale depth), a regular subgrid beyond that
    #[arg(long = "energy-samples", value_name = "N", default_value_t = DEFAULT_ENERGY_SAMPLES)]
    pub samples: usize,
}

/// Whether the solid synthesizer may mirror a role's exemplar.
#[derive(Args, Clone, Debug)]
pub struct OrientationRule {
    /// Whether a role may see its exemplar mirrored left-right: auto does so where the
    /// exemplars' diagonal preferences cannot all hold in one volume (docs/solid.md, "Diagonal
    /// orientation"; the line `orientation:` tells what was done). In `bench solid` (unless
    /// --no-ablations) a case whose role the rule mirrored is also synthesized as given
    #[arg(long = "orientation", value_name = "ORIENTATION", value_enum, default_value_t = RoleOrientation::Auto)]
    pub rule: RoleOrientation,
}
