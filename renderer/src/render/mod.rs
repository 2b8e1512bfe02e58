//! The path tracer on the device: scene upload, one dispatch per sample pass, progressive
//! accumulation into a float film, and the film read back with its AOVs.

mod error;
mod frame;
pub(crate) mod path_tracer;
mod stores;

pub use error::RenderError;
pub use frame::GpuFrame;
pub use path_tracer::{PassReport, PathTracer, RenderStats};
pub use stores::{
    BakedStoreInfo, GpuStoreRecord, SceneStore, SceneStores, StoreRead, SynthesisInfo, NO_STORE,
};

/// One bit per kind code (`STORE_KIND_*`, `MATERIAL_*`, `TEXTURE_*`): the path tracer's
/// specialization constants, with which it compiles only the store lookups, BSDFs and
/// procedural textures a scene uses (`glsl/include/render/material.glsl`; on lavapipe the
/// unused glint BSDF alone cost about 13 s of pipeline build and 1.6x the tracing time).
pub(crate) fn kinds_mask(kinds: impl Iterator<Item = u32>) -> u32 {
    kinds.fold(0, |mask, kind| mask | 1 << kind)
}
