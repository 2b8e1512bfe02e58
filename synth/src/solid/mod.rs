//! Solid texture synthesis from 2D exemplars (Dong, Lefebvre, Tong & Drettakis 2008): the 2D
//! synthesizer of `synth/` extended to a volume. Three exemplar roles `E_x`, `E_y`, `E_z`
//! ([`roles`](self) fixes their axes), per-level 3D candidates (coordinate triples with a
//! consistent crossbar that form coherent patches), and a volume synthesizer over any box of
//! the unbounded volume, each on the GPU with an exact CPU reference. See `docs/solid.md`.

mod analysis;
mod axis_quality;
mod balance;
mod candidates;
mod candidates_cache;
pub(crate) mod candidates_gpu;
mod candidates_host;
mod closure;
mod consistency;
mod cpu;
mod defaults;
pub(crate) mod gpu;
mod jitter;
pub mod lazy;
mod loop_budget;
mod nrrd;
mod orientation;
mod plan;
mod recipe;
mod relief;
mod roles;
mod schedule;
mod slab;
mod slices;
mod strip_tree;
mod strips;
mod volume;

pub use analysis::{analyze_solid, pack_rgb, unpack_rgb, RoleLevel, SolidAnalysis, SolidLevel};
pub use axis_quality::{
    axis_quality, role_scorers, slice_ratios, AxisQuality, ImageScorer, SliceRatios, QUALITY_SLICES,
};
pub use balance::{
    balance_finest_levels, balance_usage, DEFAULT_BALANCE, MAX_BALANCE, MAX_PENALTY, PILOT_ORIGIN,
    PILOT_SEED, PILOT_SIDE,
};
pub use candidates::{
    candidates_cpu, coherence_step_cpu, search_cpu, triples_cpu, unit_step, CandidateParams,
    CandidateSets, LevelReport, SolidCandidates, StripMatches, DEFAULT_S, KEPT, MAX_CANDIDATES,
    MAX_COHERENCE_ITERATIONS, MAX_S,
};
pub use candidates_cache::{
    candidates_cached, candidates_key, decode_candidates, encode_candidates, CANDIDATES_CACHE_KIND,
    CANDIDATES_FORMAT_VERSION,
};
pub use candidates_gpu::GpuCandidates;
pub use candidates_host::{candidates_host, CandidateBuilder};
pub use closure::advance_closure;
pub use consistency::{triple_consistency, triple_spread, TripleConsistency};
pub use cpu::{
    correct_subpass_3d, correct_voxel, synthesize_solid_cpu, upsample_jitter_3d, upsample_voxel,
};
pub use defaults::{
    default_solid_jitter, default_solid_passes, solid_jitter_or_default, solid_passes_or_default,
    DEFAULT_SOLID_COARSE_JITTER, DEFAULT_SOLID_FINEST_PASSES, DEFAULT_SOLID_FINE_JITTER,
    DEFAULT_SOLID_PARALLEL_LEVELS, DEFAULT_SOLID_PASSES,
};
pub use gpu::GpuSolidSynthesizer;
pub use jitter::jitter3;
pub use loop_budget::{LOOP_BUDGET, LOOP_LIMIT};
pub use nrrd::{decode_nrrd, encode_nrrd, RgbVolume};
pub use orientation::{
    exemplar_diagonal, mirrored, role_to_mirror, Mirroring, Orientation, MIN_DIAGONAL_CORRELATION,
};
pub use plan::{plan_boxes, plan_levels, LevelPlan, Subpass, VolumeBox, CLASSES_3D, SUBPASSES_3D};
pub use recipe::{
    PreparedSolid, SolidCube, SolidRecipe, SolidSchedule, SolidSources, DEFAULT_SOLID_SEED,
};
pub use relief::{role_texel, voxel_texel, SolidRelief};
pub use roles::{
    image_axis, project, shared_axis, SolidExemplars, MAX_SOLID_SIDE, MIN_SOLID_SIDE, ROLES,
    ROLE_AXES, ROLE_NAMES,
};
pub use schedule::{level_schedules, ordered_schedules, LevelSchedule, ALL_CLASSES};
pub use slab::candidate_slab;
pub use slices::{colour_slice, oblique, slice};
pub use strips::{strip_distance, DEFAULT_STRIP, MAX_STRIP};
pub use volume::{
    check_box, voxel_colour, LevelTriples, SolidSynthesis, MAX_VOLUME_ORIGIN, MAX_VOLUME_SIDE,
};
