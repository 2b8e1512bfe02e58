//! The dense-array baseline: one `u32` per key of the universe, `HASH_NOT_FOUND` where no key
//! is defined. One read per query: the practical limit of any spatial lookup.

use super::error::HashError;
use super::kernels::HashKernels;
use super::keys::Universe;
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult, Recorder};
use crate::kernels::hash;
use crate::shader_constants::HASH_NOT_FOUND;
use std::sync::Arc;

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ScatterPush<'a> {
        dense: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        payloads: DeviceAddress<'a>,
        n: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct QueryPush<'a> {
        dense: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
    }
}

/// A dense array over a universe.
pub struct DenseTable {
    kernels: Arc<HashKernels>,
    dense: GpuBuffer<u32>,
}

impl DenseTable {
    /// Stores `payloads[..n]` at `keys[..n]` (keys are not checked: this is the baseline).
    ///
    /// # Errors
    /// A universe whose array exceeds the device's buffer limits.
    pub fn build(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> Result<DenseTable, HashError> {
        crate::prims::check_len("hash keys", n, keys.len().min(payloads.len()))?;
        let count = universe.key_count();
        if count > crate::prims::MAX_ELEMENTS as u64 {
            return Err(HashError::InvalidArgument(format!(
                "a dense array over {} needs {count} elements",
                universe.describe()
            )));
        }
        let gpu = &kernels.gpu;
        let dense = GpuBuffer::<u32>::new(gpu, "dense array", count as usize)?;
        gpu.submit(|rec| {
            rec.fill(&dense, HASH_NOT_FOUND);
            let push = ScatterPush {
                dense: dense.address(),
                keys: keys.address(),
                payloads: payloads.address(),
                n: n as u32,
            };
            let k = kernels.kernel(&hash::DENSE_SCATTER)?;
            rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
        })?;
        Ok(DenseTable {
            kernels: kernels.clone(),
            dense,
        })
    }

    /// Records `results[i]` = `dense[keys[i]]`.
    pub fn record_query(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        results: &GpuBuffer<u32>,
        n: usize,
    ) -> GpuResult<()> {
        crate::prims::check_len("hash queries", n, keys.len().min(results.len()))?;
        let push = QueryPush {
            dense: self.dense.address(),
            keys: keys.address(),
            results: results.address(),
            n: n as u32,
        };
        let k = self.kernels.kernel(&hash::DENSE_QUERY)?;
        rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
    }

    /// Exact GPU bytes.
    pub fn bytes(&self) -> u64 {
        self.dense.bytes()
    }
}
