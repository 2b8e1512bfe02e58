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
