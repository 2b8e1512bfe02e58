//! Every hash kernel, built once per device and shared by the tables (pipelines are compiled at
//! their first dispatch on lavapipe, so rebuilding a table must not rebuild them).

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
    pub insert: Kernel,
    pub max_age: Kernel,
    pub set_ages: Kernel,
    /// The query kernel specialized for the coherent probe (`PROBE`, constant 1) ...
    pub query_coherent: Kernel,
    /// ... and for the random one.
    pub query_random: Kernel,
}

impl RobinHoodKernels {
    fn new(gpu: &Gpu, defs: [&'static KernelDef; 4]) -> GpuResult<RobinHoodKernels> {
        let [insert, max_age, set_ages, query] = defs;
        let probe =
            |p: Probe| Kernel::with_constants(gpu, query, DEFAULT_WORKGROUP_SIZE, &[(1, p.id())]);
        Ok(RobinHoodKernels {
            insert: Kernel::new(gpu, insert)?,
            max_age: Kernel::new(gpu, max_age)?,
            set_ages: Kernel::new(gpu, set_ages)?,
            query_coherent: probe(Probe::Coherent)?,
            query_random: probe(Probe::Random)?,
        })
    }

    /// The query kernel of `probe`.
    pub fn query(&self, probe: Probe) -> &Kernel {
        match probe {
            Probe::Coherent => &self.query_coherent,
            Probe::Random => &self.query_random,
        }
    }
}

/// All kernels of the hash tables, plus the primitives they use.
pub struct HashKernels {
    pub(crate) gpu: Gpu,
    pub(crate) cells64: RobinHoodKernels,
    pub(crate) cells32: RobinHoodKernels,
    pub(crate) open_addressing: Kernel,
    pub(crate) cuckoo_insert: Kernel,
    pub(crate) cuckoo_query: Kernel,
    pub(crate) dense_scatter: Kernel,
    pub(crate) dense_query: Kernel,
    pub(crate) check_keys: Kernel,
    pub(crate) sort: Mutex<RadixSort>,
    pub(crate) reduce: Mutex<Reduce>,
}

impl HashKernels {
    /// Builds every kernel for `gpu`.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<HashKernels>> {
        Ok(Arc::new(HashKernels {
            gpu: gpu.clone(),
            cells64: RobinHoodKernels::new(
                gpu,
                [
                    &hash::ROBIN_HOOD_INSERT64,
                    &hash::ROBIN_HOOD_MAX_AGE64,
                    &hash::ROBIN_HOOD_SET_AGES64,
                    &hash::ROBIN_HOOD_QUERY64,
                ],
            )?,
            cells32: RobinHoodKernels::new(
                gpu,
                [
                    &hash::ROBIN_HOOD_INSERT32,
                    &hash::ROBIN_HOOD_MAX_AGE32,
                    &hash::ROBIN_HOOD_SET_AGES32,
                    &hash::ROBIN_HOOD_QUERY32,
                ],
            )?,
            open_addressing: Kernel::new(gpu, &hash::OPEN_ADDRESSING_AGES)?,
            cuckoo_insert: Kernel::new(gpu, &hash::CUCKOO_INSERT)?,
            cuckoo_query: Kernel::new(gpu, &hash::CUCKOO_QUERY)?,
            dense_scatter: Kernel::new(gpu, &hash::DENSE_SCATTER)?,
            dense_query: Kernel::new(gpu, &hash::DENSE_QUERY)?,
            check_keys: Kernel::new(gpu, &hash::CHECK_KEYS)?,
            sort: Mutex::new(RadixSort::new(gpu)?),
            reduce: Mutex::new(Reduce::new(gpu)?),
        }))
    }

    pub(crate) fn robin_hood(&self, width: CellWidth) -> &RobinHoodKernels {
        match width {
            CellWidth::Bits64 => &self.cells64,
            CellWidth::Bits32 => &self.cells32,
        }
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
