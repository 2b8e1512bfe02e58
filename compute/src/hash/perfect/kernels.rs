//! The perfect-hash kernels and the primitives they use, built once per device.

use crate::gpu::{Gpu, GpuResult, Kernel};
use crate::kernels::hash;
use crate::prims::{Compactor, Scan};
use std::sync::{Arc, Mutex};

/// Every kernel of the perfect-hash construction and lookups (pipelines compile at their first
/// dispatch on lavapipe, so builders share one set).
pub struct PerfectKernels {
    pub(crate) gpu: Gpu,
    pub(crate) prepare: Kernel,
    pub(crate) scatter: Kernel,
    pub(crate) classes: Kernel,
    pub(crate) order: Kernel,
    pub(crate) propose: Kernel,
    pub(crate) verify: Kernel,
    pub(crate) free_count: Kernel,
    pub(crate) assign: Kernel,
    pub(crate) pack: Kernel,
    pub(crate) fill: Kernel,
    pub(crate) query: Kernel,
    pub(crate) blocked_query: Kernel,
    pub(crate) scan: Mutex<Scan>,
    pub(crate) compact: Mutex<Compactor>,
}

impl PerfectKernels {
    /// Builds every kernel for `gpu`.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<PerfectKernels>> {
        Ok(Arc::new(PerfectKernels {
            gpu: gpu.clone(),
            prepare: Kernel::new(gpu, &hash::PERFECT_PREPARE)?,
            scatter: Kernel::new(gpu, &hash::PERFECT_SCATTER)?,
            classes: Kernel::new(gpu, &hash::PERFECT_CLASSES)?,
            order: Kernel::new(gpu, &hash::PERFECT_ORDER)?,
            propose: Kernel::new(gpu, &hash::PERFECT_PROPOSE)?,
            verify: Kernel::new(gpu, &hash::PERFECT_VERIFY)?,
            free_count: Kernel::new(gpu, &hash::PERFECT_FREE_COUNT)?,
            assign: Kernel::new(gpu, &hash::PERFECT_ASSIGN)?,
            pack: Kernel::new(gpu, &hash::PERFECT_PACK)?,
            fill: Kernel::new(gpu, &hash::PERFECT_FILL)?,
            query: Kernel::new(gpu, &hash::PERFECT_QUERY)?,
            blocked_query: Kernel::new(gpu, &hash::PERFECT_BLOCKED_QUERY)?,
            scan: Mutex::new(Scan::new(gpu)?),
            compact: Mutex::new(Compactor::new(gpu)?),
        }))
    }

    /// The device the kernels belong to.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}
