//! Why a render failed.

use crate::output::OutputError;
use crate::shading::ShadingError;
use lazysolid_compute::gpu::GpuError;

/// A render failure: device, shading data (e.g. an unreadable environment map) or output.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A Vulkan failure or a device limit.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// Materials, lights or the environment could not be prepared.
    #[error(transparent)]
    Shading(#[from] ShadingError),
    /// The film could not be assembled or written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A setting the renderer cannot honour.
    #[error("{0}")]
    Settings(String),
}
