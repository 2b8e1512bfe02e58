//! Parallel, deterministic texture synthesis in appearance space (Lefebvre & Hoppe 2005 run on
//! the appearance vectors of Lefebvre & Hoppe 2006): the 2D core that lazy solid synthesis
//! extends to 3D.
//!
//! Pipeline: an image ([`DecodedImage`], any size) → [`fit_plane`] / [`fit_solid`] (crop or
//! resample as each synthesizer needs, with an [`ExemplarFit`] saying what was done) →
//! [`Exemplar`] → [`analyze`] (CPU preprocessing: Gaussian stack, 8D quantized
//! appearance vectors, k-coherence sets) → per pyramid level upsampling, jitter and correction
//! of exemplar coordinates, on the GPU ([`GpuSynthesizer`]) or on the CPU reference
//! ([`synthesize_cpu`]), which agree exactly. Any window of the unbounded output plane can be
//! synthesized on its own ([`plan_regions`] gives the padding); [`EnergyKernel`] (or [`energy_cpu`]) scores the result.
//! See `docs/synthesis.md`.
//!
//! The crate sits between `lazysolid-compute` (the Vulkan core, primitives, hashes and stores it
//! dispatches on and fills) and the renderer; it owns the `glsl/synth/` kernels and their
//! constants ([`shader_constants`]).

mod analysis;
mod analysis_cache;
mod appearance;
pub mod cache;
mod coherence;
mod coords;
mod cpu;
mod decode;
pub(crate) mod energy;
mod error;
mod exemplar;
pub mod feature;
mod fit;
pub(crate) mod gpu;
mod jitter;
pub mod multiscale;
mod neighbourhood;
mod params;
mod pat;
mod period;
mod plan;
mod push_registry;
pub mod quality;
pub mod relief;
mod repetition;
mod resample;
pub mod shader_constants;
pub mod solid;
mod stack;
mod synthesis;

/// Kernels compiled from `glsl/synth/` at build time, one module per folder.
pub mod kernels {
    include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
}

pub use analysis::{
    analyze, AnalysisParams, ExemplarAnalysis, LevelAnalysis, DEFAULT_COHERENCE_K,
    DEFAULT_COHERENCE_SPREAD, MAX_COHERENCE_K, MAX_COHERENCE_SPREAD,
};
pub use analysis_cache::{
    analysis_key, analyze_cached, decode_analysis, encode_analysis, ANALYSIS_CACHE_KIND,
    ANALYSIS_FORMAT_VERSION,
};
pub use appearance::{appearance_distance, APPEARANCE_DIMS, APPEARANCE_QUANT_MAX};
pub use cache::{CacheOutcome, DiskCache};
pub use coherence::MAX_POOL;
pub use coords::{pack, unpack};
pub use cpu::{correct_subpass, synthesize_cpu, upsample_jitter};
pub use decode::{ChannelLayout, DecodedImage, MAX_DECODE_SIDE};
pub use energy::{
    energy_cpu, energy_positions, histogram_distance, EnergyKernel, EnergyReport, ENERGY_RADIUS,
};
pub use error::{SynthError, SynthResult};
pub use exemplar::{Exemplar, MAX_EXEMPLAR_SIDE, MIN_EXEMPLAR_SIDE};
pub use fit::{
    crop, fit_plane, fit_solid, load_plane, load_solid, plan_map, plan_plane, plan_solid, CropRect,
    ExemplarFit, FitMode, FitPlan, FittedExemplar,
};
pub use gpu::{GpuSynthesizer, LevelTimes};
pub use jitter::{hash4, jitter};
pub use neighbourhood::{
    exemplar_neighbourhoods, neighbourhood_distance, pack_i8_words, synthesized_neighbourhood,
    DIAGONALS, NEIGHBOURHOOD_DIMS,
};
pub use params::{
    default_jitter, default_passes, default_passes_for, default_plane_jitter, jitter_or_default,
    layout_level, pass_schedule, passes_or_default, SynthParams, DEFAULT_COARSE_JITTER,
    DEFAULT_FINEST_PASSES, DEFAULT_FINE_JITTER, DEFAULT_PASSES, DEFAULT_PERIOD_PENALTY, JITTER_ONE,
    MAX_PASSES, MAX_PERIOD_PENALTY,
};
pub use pat::{decode_pattern, Pattern};
pub use period::{period_reach, spans_period, PERIOD_TOLERANCE};
pub use plan::{correction_padding, plan_regions, Region, SUBPASSES};
pub use push_registry::push_registry;
pub use repetition::{period_repetition, REPETITION_TOLERANCE};
pub use resample::{resample_lanczos3, resample_lanczos3_f32, Border};
pub use synthesis::{check_window, LevelCoords, Synthesis, MAX_WINDOW_ORIGIN, MAX_WINDOW_SIDE};
