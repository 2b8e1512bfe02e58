//! Single-pass cuckoo hashing on the GPU (Alcantara et al.): one table, four hash functions, a
//! bounded chain of evictions per key, and a rebuild with new hash constants when keys are
//! left unplaced. The constant-probe baseline of the coherent hash.

use super::cuckoo_cpu::CuckooFunctions;
use super::error::HashError;
use super::kernels::HashKernels;
use super::keys::Universe;
use super::robin_hood::table_size_for;
use super::validate::validate_entries;
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult, Recorder};
use crate::kernels::hash;
use crate::shader_constants::HASH_NOT_FOUND;
use std::sync::Arc;

/// How a cuckoo table is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CuckooConfig {
    /// keys / cells.
    pub load_factor: f64,
    /// Seed of the hash constants.
    pub seed: u64,
    /// Builds tried with fresh constants before giving up.
    pub attempts: u32,
    /// Check keys and payloads first.
    pub validate: bool,
}

impl Default for CuckooConfig {
    fn default() -> Self {
        CuckooConfig {
            load_factor: 0.85,
            seed: 0x5eed,
            attempts: 8,
            validate: true,
        }
    }
}

/// Swaps one key may make before it counts as unplaced: 7 log2(n), at least 32 (the bound
/// the CUDPP lineage of this scheme uses).
pub fn max_iterations(n: usize) -> u32 {
    (7 * (usize::BITS - n.max(1).leading_zeros())).max(32)
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct InsertPush<'a> {
        cells: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        payloads: DeviceAddress<'a>,
        counters: DeviceAddress<'a>,
        a: [u32; 4],
        b: [u32; 4],
        n: u32,
        table_size: u32,
        max_iterations: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct QueryPush<'a> {
        cells: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        a: [u32; 4],
        b: [u32; 4],
        n: u32,
        table_size: u32,
    }
}

/// A cuckoo hash table on the GPU. Keys must be below 2³² − 1.
pub struct CuckooTable {
    kernels: Arc<HashKernels>,
    cells: GpuBuffer<u64>,
    table_size: u32,
    /// The hash functions that succeeded.
    pub functions: CuckooFunctions,
    /// Builds that failed before this one (each with fresh constants).
    pub failed_attempts: u32,
    len: u64,
}

impl CuckooTable {
    /// Builds a table of `keys[..n]` → `payloads[..n]`.
    ///
    /// # Errors
    /// Duplicate keys, keys outside `universe` or ≥ 2³² − 1, payloads equal to
    /// `HASH_NOT_FOUND`, and construction failure with every set of constants.
    pub fn build(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        config: CuckooConfig,
    ) -> Result<CuckooTable, HashError> {
        if !(config.load_factor > 0.0 && config.load_factor <= 1.0) {
            return Err(HashError::InvalidArgument(format!(
                "load factor {} is outside (0, 1]",
                config.load_factor
            )));
        }
        if universe.key_count() > u32::MAX as u64 {
            return Err(HashError::UniverseTooLarge {
                universe: universe.describe(),
                key_bits: universe.key_bits(),
                cell_bits: 64,
            });
        }
        crate::prims::check_len("hash keys", n, keys.len().min(payloads.len()))?;
        if config.validate {
            let limit = (HASH_NOT_FOUND - 1, "cuckoo cells".to_string(), 32);
            validate_entries(kernels, &universe, keys, payloads, n, limit)?;
        }
        let table_size = table_size_for(n as u64, config.load_factor)?;
        let mut table = CuckooTable {
            kernels: kernels.clone(),
            cells: GpuBuffer::new(&kernels.gpu, "cuckoo cells", table_size as usize)?,
            table_size,
            functions: CuckooFunctions::from_seed(config.seed, 0),
            failed_attempts: 0,
            len: n as u64,
        };
        table.insert_with_retries(keys, payloads, n, &config)?;
        Ok(table)
    }

    /// Clears the table and inserts `keys[..n]` with the current hash constants; when keys are
    /// left unplaced, tries the next constants of `config.seed`, up to `config.attempts`
    /// attempts in all. Returns the GPU time of every attempt in ms.
    fn insert_with_retries(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        config: &CuckooConfig,
    ) -> Result<f64, HashError> {
        let gpu = self.kernels.gpu.clone();
        let mut total = 0.0;
        let mut failed = 0;
        for _ in 0..config.attempts.max(1) {
            let counters = GpuBuffer::<u32>::zeroed(&gpu, "cuckoo counters", 4)?;
            let ((), t) = gpu.submit_timed(|rec| {
                rec.timestamp()?;
                rec.fill(&self.cells, 0);
                self.record_insert(rec, keys, payloads, n, &counters)?;
                rec.timestamp()
            })?;
            total += (t[1] - t[0]) * 1e-6;
            let c = counters.read()?;
            if c[1] > 0 {
                return Err(HashError::DuplicateKey {
                    key: 0,
                    count: c[1] as u64,
                });
            }
            if c[0] == 0 {
                return Ok(total);
            }
            failed = c[0];
            self.failed_attempts += 1;
            self.functions = CuckooFunctions::from_seed(config.seed, self.failed_attempts);
        }
        Err(HashError::CuckooFailed {
            attempts: config.attempts.max(1),
            load_factor: n as f64 / self.table_size as f64,
            failed,
        })
    }

    /// Builds from host slices.
    pub fn build_from_slices(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        keys: &[u64],
        payloads: &[u32],
        config: CuckooConfig,
    ) -> Result<CuckooTable, HashError> {
        let (k, p) = kernels.upload_pairs(keys, payloads)?;
        Self::build(kernels, universe, &k, &p, keys.len(), config)
    }

    fn record_insert(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        counters: &GpuBuffer<u32>,
    ) -> GpuResult<()> {
        let push = InsertPush {
            cells: self.cells.address(),
            keys: keys.address(),
            payloads: payloads.address(),
            counters: counters.address(),
            a: self.functions.a,
            b: self.functions.b,
            n: n as u32,
            table_size: self.table_size,
            max_iterations: max_iterations(n),
        };
        let k = self.kernels.kernel(&hash::CUCKOO_INSERT)?;
        rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
    }

    /// Rebuilds from the same keys and returns the GPU time of clearing and inserting in ms
    /// (what the insertion benchmarks measure). Parallel cuckoo insertion depends on the order
    /// in which invocations swap, so the same constants can fail on a rebuild: then new ones are
    /// tried, as a build does, and the time of every attempt counts.
    pub fn rebuild_timed(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        config: &CuckooConfig,
    ) -> Result<f64, HashError> {
        self.insert_with_retries(keys, payloads, n, config)
    }

    /// Records `results[i]` = the payload of `keys[i]` or `HASH_NOT_FOUND`.
    pub fn record_query(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        results: &GpuBuffer<u32>,
        n: usize,
    ) -> GpuResult<()> {
        crate::prims::check_len("hash queries", n, keys.len().min(results.len()))?;
        let push = QueryPush {
            cells: self.cells.address(),
            keys: keys.address(),
            results: results.address(),
            a: self.functions.a,
            b: self.functions.b,
            n: n as u32,
            table_size: self.table_size,
        };
        let k = self.kernels.kernel(&hash::CUCKOO_QUERY)?;
        rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
    }

    /// Queries `keys` and reads the results back.
    pub fn query(&self, keys: &[u64]) -> GpuResult<Vec<u32>> {
        self.kernels
            .run_queries(keys, |rec, k, r, n| self.record_query(rec, k, r, n))
    }

    /// The cells.
    pub fn cells(&self) -> GpuResult<Vec<u64>> {
        self.cells.read()
    }

    /// Exact GPU bytes of the table.
    pub fn bytes(&self) -> u64 {
        self.cells.bytes()
    }

    /// Cells.
    pub fn table_size(&self) -> u32 {
        self.table_size
    }

    /// Keys stored.
    pub fn len(&self) -> u64 {
        self.len
    }

    /// True when no key is stored.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}
