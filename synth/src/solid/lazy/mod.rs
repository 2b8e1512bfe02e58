//! Lazy solid synthesis: only the voxels a set of requested finest-level voxels depends on,
//! level by level, equal bit for bit to the full volume on the requested voxels (Dong et al.
//! 2008; thesis 003 lines 1083–1096).

mod correct_parts;
mod deps;
pub(crate) mod gpu;
mod keys;
mod matter;
mod policy;
mod state_cpu;
pub(crate) mod visit_order;
pub(crate) mod walk;

pub use correct_parts::CorrectParts;
pub use deps::{
    class_index, dependencies_cpu, finest_growth_cpu, Dependencies, LevelDeps, PLANE_NEIGHBOURS,
};
pub use gpu::{GpuLazySolid, LazyReport, LAZY_MARGIN};
pub use keys::{
    check_request, lazy_key, lazy_position, tag, untag, LAZY_AXIS_BITS, LAZY_BIAS, MAX_LAZY_COORD,
    STAGE_BITS, STAGE_MAX,
};
pub use matter::{
    CutInfo, MatterColours, MatterError, MatterSpec, MatterStore, MatterVoxels, SharedLazy,
    StoredMatter, SynthesisInfo,
};
pub use policy::{LevelKeep, MemoryPolicy, DEFAULT_STATE_BUDGET_MB, LAZY_CHUNK_VOXELS};
pub use state_cpu::LazySolidCpu;
pub use visit_order::{order_key, stage_range, StageRanges, VisitOrder};
