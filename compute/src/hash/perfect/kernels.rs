//! What the perfect-hash builders share on one device: kernels come from the device's kernel
//! cache when first used; the scan and the compaction keep their scratch here between builds.

use crate::gpu::{Gpu, GpuResult};
use crate::prims::{Compactor, Scan};
use std::sync::{Arc, Mutex};

/// The perfect-hash builders' and lookups' shared context on one device.
pub struct PerfectKernels {
    pub(crate) gpu: Gpu,
    pub(crate) scan: Mutex<Scan>,
    pub(crate) compact: Mutex<Compactor>,
}

impl PerfectKernels {
    /// The context for `gpu`; builds no pipeline.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<PerfectKernels>> {
        Ok(Arc::new(PerfectKernels {
            gpu: gpu.clone(),
            scan: Mutex::new(Scan::new(gpu)?),
            compact: Mutex::new(Compactor::new(gpu)?),
        }))
    }

    /// The device the kernels belong to.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}
