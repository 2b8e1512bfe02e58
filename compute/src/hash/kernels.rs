//! What the hash tables share on one device: the kernels (fetched from the device's kernel
//! cache at their first use, so building a table builds no pipeline twice and a table never
//! builds the pipelines of another kind), and the primitives whose scratch they reuse.

use super::cell::CellWidth;
use super::error::HashError;
use super::probe::Probe;
use crate::gpu::{Gpu, GpuBuffer, GpuResult, Kernel, KernelDef, Recorder};
use crate::kernels::hash;
use crate::prims::{RadixSort, Reduce};
use crate::shader_constants::DEFAULT_WORKGROUP_SIZE;
use std::sync::{Arc, Mutex};

/// The Robin Hood kernels of one cell width.
pub(crate) struct RobinHoodKernels {
    pub insert: &'static KernelDef,
    pub max_age: &'static KernelDef,
    pub set_ages: &'static KernelDef,
    /// Specialized per probe sequence (`PROBE`, constant 1).
    query: &'static KernelDef,
}

const CELLS64: RobinHoodKernels = RobinHoodKernels {
    insert: &hash::ROBIN_HOOD_INSERT64,
    max_age: &hash::ROBIN_HOOD_MAX_AGE64,
    set_ages: &hash::ROBIN_HOOD_SET_AGES64,
    query: &hash::ROBIN_HOOD_QUERY64,
};

const CELLS32: RobinHoodKernels = RobinHoodKernels {
    insert: &hash::ROBIN_HOOD_INSERT32,
    max_age: &hash::ROBIN_HOOD_MAX_AGE32,
    set_ages: &hash::ROBIN_HOOD_SET_AGES32,
    query: &hash::ROBIN_HOOD_QUERY32,
};

impl RobinHoodKernels {
    /// The query kernel of `probe`.
    pub fn query(&self, gpu: &Gpu, probe: Probe) -> GpuResult<Arc<Kernel>> {
        gpu.kernel_with(self.query, DEFAULT_WORKGROUP_SIZE, &[(1, probe.id())])
    }
}

/// The hash tables' shared context on one device: kernels come from the device's cache when
/// first used; the radix sort (key validation) and the reduction (maximum age) keep their
/// scratch here between builds.
pub struct HashKernels {
    pub(crate) gpu: Gpu,
    pub(crate) sort: Mutex<RadixSort>,
    pub(crate) reduce: Mutex<Reduce>,
}

impl HashKernels {
    /// The context for `gpu`; builds no pipeline.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<HashKernels>> {
        Ok(Arc::new(HashKernels {
            gpu: gpu.clone(),
            sort: Mutex::new(RadixSort::new(gpu)?),
            reduce: Mutex::new(Reduce::new(gpu)?),
        }))
    }

    pub(crate) fn robin_hood(&self, width: CellWidth) -> &'static RobinHoodKernels {
        match width {
            CellWidth::Bits64 => &CELLS64,
            CellWidth::Bits32 => &CELLS32,
        }
    }

    /// `def` from the device's kernel cache.
    pub(crate) fn kernel(&self, def: &'static KernelDef) -> GpuResult<Arc<Kernel>> {
        self.gpu.kernel(def)
    }

    /// The device the kernels belong to.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}

impl HashKernels {
    /// Uploads `(key, payload)` pairs for a build.
    pub(crate) fn upload_pairs(
        &self,
        keys: &[u64],
        payloads: &[u32],
    ) -> Result<(GpuBuffer<u64>, GpuBuffer<u32>), HashError> {
        if keys.len() != payloads.len() {
            return Err(HashError::InvalidArgument(format!(
                "{} keys but {} payloads",
                keys.len(),
                payloads.len()
            )));
        }
        Ok((
            GpuBuffer::from_slice(&self.gpu, "hash keys", keys)?,
            GpuBuffer::from_slice(&self.gpu, "hash payloads", payloads)?,
        ))
    }

    /// Uploads `keys`, records the queries with `record(rec, keys, results, n)`, submits and
    /// reads the results back.
    pub(crate) fn run_queries(
        &self,
        keys: &[u64],
        record: impl FnOnce(&mut Recorder<'_>, &GpuBuffer<u64>, &GpuBuffer<u32>, usize) -> GpuResult<()>,
    ) -> GpuResult<Vec<u32>> {
        let k = GpuBuffer::from_slice(&self.gpu, "hash queries", keys)?;
        let r = GpuBuffer::<u32>::new(&self.gpu, "hash query results", keys.len())?;
        self.gpu.submit(|rec| record(rec, &k, &r, keys.len()))?;
        r.read()
    }
}
