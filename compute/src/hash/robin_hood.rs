//! The Robin Hood tables on the GPU: coherent (García et al. 2011) or random probing, one
//! invocation per key, the max-age table folded into the cells afterwards.

use super::cell::{CellFormat, CellWidth};
use super::error::HashError;
use super::kernels::HashKernels;
use super::keys::Universe;
use super::probe::{fastmod_multiplier, Probe};
use super::validate::{validate_entries, validate_keys_gpu};
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult, Recorder};
use crate::prims::ReduceOp;
use crate::shader_constants::HASH_MAX_AGE;
use std::sync::Arc;

/// How a Robin Hood table is built and grown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RobinHoodConfig {
    /// Probe sequence.
    pub probe: Probe,
    /// Cell width.
    pub width: CellWidth,
    /// Load factor of a fresh build: |H| = ceil(keys / load_factor), made odd.
    pub load_factor: f64,
    /// Highest load factor that inserts may reach.
    pub max_load_factor: f64,
    /// When the 4-bit age would overflow or an insert would pass `max_load_factor`, rebuild at
    /// a larger size (and say so in the report) instead of failing.
    pub grow: bool,
    /// Check keys (duplicates, universe) and payloads before building or inserting.
    pub validate: bool,
    /// Count the keys at each age (atomics; leave off when timing).
    pub histogram: bool,
}

impl Default for RobinHoodConfig {
    fn default() -> Self {
        RobinHoodConfig {
            probe: Probe::Coherent,
            width: CellWidth::Bits64,
            load_factor: 0.85,
            max_load_factor: 0.99,
            grow: true,
            validate: true,
            histogram: false,
        }
    }
}

/// What a build or insert did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildReport {
    /// Keys in the table.
    pub keys: u64,
    /// Cells.
    pub table_size: u32,
    /// keys / cells.
    pub load_factor: f64,
    /// Largest probe age of any key.
    pub max_age: u32,
    /// Keys at each age 0..=15 (with `histogram`).
    pub age_histogram: Option<Vec<u64>>,
    /// Every rebuild at a larger size, with its reason.
    pub rebuilds: Vec<String>,
}

/// Scratch of one recorded insert ([`RobinHoodTable::record_append`]).
pub struct AppendScratch {
    backup: CellBuffer,
    counters: GpuBuffer<u32>,
    mat: GpuBuffer<u32>,
    ages: GpuBuffer<u32>,
}

pub(crate) enum CellBuffer {
    Wide(GpuBuffer<u64>),
    Compact(GpuBuffer<u32>),
}

impl CellBuffer {
    fn new(gpu: &Gpu, width: CellWidth, size: u32) -> GpuResult<CellBuffer> {
        Ok(match width {
            CellWidth::Bits64 => CellBuffer::Wide(GpuBuffer::new(
                gpu,
                "robin hood cells (64-bit)",
                size as usize,
            )?),
            CellWidth::Bits32 => CellBuffer::Compact(GpuBuffer::new(
                gpu,
                "robin hood cells (32-bit)",
                size as usize,
            )?),
        })
    }

    fn address(&self) -> DeviceAddress<'_> {
        match self {
            CellBuffer::Wide(b) => b.address(),
            CellBuffer::Compact(b) => b.address(),
        }
    }

    fn bytes(&self) -> u64 {
        match self {
            CellBuffer::Wide(b) => b.bytes(),
            CellBuffer::Compact(b) => b.bytes(),
        }
    }

    fn clear(&self, rec: &mut Recorder<'_>) {
        match self {
            CellBuffer::Wide(b) => rec.fill(b, 0),
            CellBuffer::Compact(b) => rec.fill(b, 0),
        }
    }

    fn copy_to(&self, rec: &mut Recorder<'_>, other: &CellBuffer) -> GpuResult<()> {
        match (self, other) {
            (CellBuffer::Wide(a), CellBuffer::Wide(b)) => rec.copy(a, 0, b, 0, a.len()),
            (CellBuffer::Compact(a), CellBuffer::Compact(b)) => rec.copy(a, 0, b, 0, a.len()),
            _ => unreachable!("backups have the table's width"),
        }
    }

    fn read(&self) -> GpuResult<Vec<u64>> {
        Ok(match self {
            CellBuffer::Wide(b) => b.read()?,
            CellBuffer::Compact(b) => b.read()?.into_iter().map(u64::from).collect(),
        })
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct InsertPush<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        keys: DeviceAddress<'a>,
        payloads: DeviceAddress<'a>,
        counters: DeviceAddress<'a>,
        n: u32,
        table_size: u32,
        key_bits: u32,
        probe: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MaxAgePush<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        mat: DeviceAddress<'a>,
        histogram: DeviceAddress<'a>,
        table_size: u32,
        key_bits: u32,
        probe: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct SetAgesPush<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        mat: DeviceAddress<'a>,
        table_size: u32,
        key_bits: u32,
        probe: u32,
        mode: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct QueryPush<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        keys: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        n: u32,
        table_size: u32,
        key_bits: u32,
    }
}

/// Cells for `keys` at `load_factor`: the smallest odd count with keys / cells ≤ load_factor.
pub(crate) fn table_size_for(keys: u64, load_factor: f64) -> Result<u32, HashError> {
    let size = ((keys as f64 / load_factor).ceil() as u64).max(1) | 1;
    if size > (crate::prims::MAX_ELEMENTS as u64) {
        return Err(HashError::InvalidArgument(format!(
            "{keys} keys at load factor {load_factor} need {size} cells, above the limit of {}",
            crate::prims::MAX_ELEMENTS
        )));
    }
    Ok(size as u32)
}

/// A Robin Hood hash table on the GPU.
pub struct RobinHoodTable {
    kernels: Arc<HashKernels>,
    universe: Universe,
    format: CellFormat,
    config: RobinHoodConfig,
    cells: CellBuffer,
    table_size: u32,
    len: u64,
    /// What the last build or insert did.
    pub report: BuildReport,
}

fn check_config(c: &RobinHoodConfig) -> Result<(), HashError> {
    let ok = c.load_factor > 0.0 && c.load_factor <= c.max_load_factor && c.max_load_factor <= 1.0;
    if !ok {
        return Err(HashError::InvalidArgument(format!(
            "load factors must satisfy 0 < load_factor ({}) <= max_load_factor ({}) <= 1",
            c.load_factor, c.max_load_factor
        )));
    }
    Ok(())
}

impl RobinHoodTable {
    /// Builds a table of `keys[..n]` → `payloads[..n]`.
    ///
    /// # Errors
    /// Duplicate keys, keys outside `universe`, payloads too wide for the cell, a universe too
    /// large for the cell width, bad load factors, and an age overflow without `grow`.
    pub fn build(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        config: RobinHoodConfig,
    ) -> Result<RobinHoodTable, HashError> {
        check_config(&config)?;
        let format = CellFormat::new(config.width, &universe)?;
        crate::prims::check_len("hash keys", n, keys.len().min(payloads.len()))?;
        if config.validate {
            Self::validate(kernels, &universe, &format, keys, payloads, n)?;
        }
        let table_size = table_size_for(n as u64, config.load_factor)?;
        let gpu = kernels.gpu.clone();
        let mut table = RobinHoodTable {
            kernels: kernels.clone(),
            universe,
            format,
            config,
            cells: CellBuffer::new(&gpu, config.width, table_size)?,
            table_size,
            len: 0,
            report: BuildReport::default(),
        };
        let mut rebuilds = Vec::new();
        loop {
            let counters = GpuBuffer::<u32>::zeroed(&gpu, "robin hood counters", 4)?;
            gpu.submit(|rec| {
                table.cells.clear(rec);
                table.record_insert(rec, keys, payloads, n, &counters)
            })?;
            let c = counters.read()?;
            if c[1] > 0 {
                // Only reachable without validation: find the key for the message.
                let check = validate_keys_gpu(kernels, keys, n, &universe)?;
                return Err(check
                    .error(n, &universe)
                    .unwrap_or(HashError::DuplicateKey {
                        key: 0,
                        count: c[1] as u64,
                    }));
            }
            if c[0] == 0 {
                break;
            }
            let lf = n as f64 / table.table_size as f64;
            if !config.grow || rebuilds.len() >= 8 {
                return Err(HashError::AgeOverflow {
                    failed: c[0],
                    max_age: HASH_MAX_AGE,
                    load_factor: lf,
                    table_size: table.table_size,
                });
            }
            let grown = table_size_for(n as u64, lf / 1.05)?.max(table.table_size + 2);
            rebuilds.push(format!("{} key(s) exceeded age {HASH_MAX_AGE} at load factor {lf:.4} in {} cells; rebuilt with {grown} cells", c[0], table.table_size));
            table.table_size = grown;
            table.cells = CellBuffer::new(&gpu, config.width, grown)?;
        }
        table.len = n as u64;
        table.finish()?;
        table.report.rebuilds = rebuilds;
        Ok(table)
    }

    /// Builds from host slices.
    pub fn build_from_slices(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        keys: &[u64],
        payloads: &[u32],
        config: RobinHoodConfig,
    ) -> Result<RobinHoodTable, HashError> {
        let (k, p) = kernels.upload_pairs(keys, payloads)?;
        Self::build(kernels, universe, &k, &p, keys.len(), config)
    }

    fn validate(
        kernels: &HashKernels,
        universe: &Universe,
        format: &CellFormat,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> Result<(), HashError> {
        let limit = (format.max_payload(), format.describe(), format.payload_bits);
        validate_entries(kernels, universe, keys, payloads, n, limit)
    }

    fn record_insert(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        counters: &GpuBuffer<u32>,
    ) -> GpuResult<()> {
        let k = self.kernels.robin_hood(self.config.width);
        let push = InsertPush {
            cells: self.cells.address(),
            fastmod_m: fastmod_multiplier(self.table_size),
            keys: keys.address(),
            payloads: payloads.address(),
            counters: counters.address(),
            n: n as u32,
            table_size: self.table_size,
            key_bits: self.format.key_bits,
            probe: self.config.probe.id(),
        };
        let insert = self.kernels.kernel(k.insert)?;
        rec.dispatch(&insert, insert.groups_for(n as u64), &[], &push)
    }

    fn record_set_ages(
        &self,
        rec: &mut Recorder<'_>,
        mat: &GpuBuffer<u32>,
        mode: u32,
    ) -> GpuResult<()> {
        let k = self.kernels.robin_hood(self.config.width);
        let push = SetAgesPush {
            cells: self.cells.address(),
            fastmod_m: fastmod_multiplier(self.table_size),
            mat: mat.address(),
            table_size: self.table_size,
            key_bits: self.format.key_bits,
            probe: self.config.probe.id(),
            mode,
        };
        let set_ages = self.kernels.kernel(k.set_ages)?;
        rec.dispatch(
            &set_ages,
            set_ages.groups_for(self.table_size as u64),
            &[],
            &push,
        )
    }

    fn record_max_age(
        &self,
        rec: &mut Recorder<'_>,
        mat: &GpuBuffer<u32>,
        histogram: Option<&GpuBuffer<u32>>,
    ) -> GpuResult<()> {
        let k = self.kernels.robin_hood(self.config.width);
        rec.fill(mat, 0);
        if let Some(h) = histogram {
            rec.fill(h, 0);
        }
        let push = MaxAgePush {
            cells: self.cells.address(),
            fastmod_m: fastmod_multiplier(self.table_size),
            mat: mat.address(),
            histogram: histogram.map_or(DeviceAddress::NULL, GpuBuffer::address),
            table_size: self.table_size,
            key_bits: self.format.key_bits,
            probe: self.config.probe.id(),
        };
        let max_age = self.kernels.kernel(k.max_age)?;
        rec.dispatch(
            &max_age,
            max_age.groups_for(self.table_size as u64),
            &[],
            &push,
        )
    }

    /// Computes MAT, folds it into the cells and fills the report.
    fn finish(&mut self) -> Result<(), HashError> {
        let gpu = self.kernels.gpu.clone();
        let mat =
            GpuBuffer::<u32>::new(&gpu, "robin hood max-age table", self.table_size as usize)?;
        let histogram = if self.config.histogram {
            Some(GpuBuffer::<u32>::new(&gpu, "robin hood age histogram", 16)?)
        } else {
            None
        };
        let max = GpuBuffer::<u32>::new(&gpu, "robin hood max age", 1)?;
        let mut reduce = self.kernels.reduce.lock().unwrap();
        gpu.submit(|rec| {
            self.record_max_age(rec, &mat, histogram.as_ref())?;
            reduce.record(rec, &mat, self.table_size as usize, ReduceOp::Max, &max)?;
            self.record_set_ages(rec, &mat, 0)
        })?;
        drop(reduce);
        self.report.keys = self.len;
        self.report.table_size = self.table_size;
        self.report.load_factor = self.len as f64 / self.table_size as f64;
        self.report.max_age = max.read()?[0];
        self.report.age_histogram = match histogram {
            Some(h) => Some(h.read()?.into_iter().map(u64::from).collect()),
            None => None,
        };
        Ok(())
    }

    /// Rebuilds the table from the same `keys[..n]` at its current size without any check, and
    /// returns the GPU time of clearing, inserting and folding the max-age table in ms: what
    /// the insertion benchmarks measure.
    pub fn rebuild_timed(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> Result<f64, HashError> {
        let gpu = self.kernels.gpu.clone();
        let counters = GpuBuffer::<u32>::zeroed(&gpu, "robin hood counters", 4)?;
        let mat =
            GpuBuffer::<u32>::new(&gpu, "robin hood max-age table", self.table_size as usize)?;
        let ((), t) = gpu.submit_timed(|rec| {
            rec.timestamp()?;
            self.cells.clear(rec);
            self.record_insert(rec, keys, payloads, n, &counters)?;
            self.record_max_age(rec, &mat, None)?;
            self.record_set_ages(rec, &mat, 0)?;
            rec.timestamp()
        })?;
        let c = counters.read()?;
        if c[0] > 0 || c[1] > 0 {
            return Err(HashError::AgeOverflow {
                failed: c[0] + c[1],
                max_age: HASH_MAX_AGE,
                load_factor: n as f64 / self.table_size as f64,
                table_size: self.table_size,
            });
        }
        self.len = n as u64;
        Ok((t[1] - t[0]) * 1e-6)
    }

    /// Makes room for `total` keys without passing `max_load_factor`: a table that would pass
    /// it is rebuilt at `load_factor` for `total` keys now (said in the report), so that a
    /// recorded insert ([`RobinHoodTable::record_append`]) of the difference meets no load
    /// limit.
    ///
    /// Returns whether it rebuilt.
    ///
    /// # Errors
    /// A size past the device's limits, or a GPU failure.
    pub fn reserve(&mut self, total: u64) -> Result<bool, HashError> {
        if total as f64 <= self.config.max_load_factor * self.table_size as f64 {
            return Ok(false);
        }
        let size = table_size_for(total, self.config.load_factor)?;
        let (keys, payloads) = self.entries()?;
        let gpu = self.kernels.gpu.clone();
        let mut grown = RobinHoodTable {
            kernels: self.kernels.clone(),
            universe: self.universe,
            format: self.format,
            config: self.config,
            cells: CellBuffer::new(&gpu, self.config.width, size)?,
            table_size: size,
            len: 0,
            report: BuildReport::default(),
        };
        let (k, p) = self.kernels.upload_pairs(&keys, &payloads)?;
        grown.fill_checked(&k, &p, keys.len())?;
        grown.report.rebuilds = vec![format!(
            "room for {total} keys in {} cells (load factor {} at most)",
            size, self.config.max_load_factor
        )];
        *self = grown;
        Ok(true)
    }

    /// An empty table with room for `room` keys at `config.load_factor`: cleared cells, no
    /// rebuild (one submission).
    ///
    /// # Errors
    /// Bad load factors, a universe too large for the cell width, a size past the device's
    /// limits, or a GPU failure.
    pub fn with_room(
        kernels: &Arc<HashKernels>,
        universe: Universe,
        room: u64,
        config: RobinHoodConfig,
    ) -> Result<RobinHoodTable, HashError> {
        check_config(&config)?;
        let format = CellFormat::new(config.width, &universe)?;
        let table_size = table_size_for(room, config.load_factor)?;
        let gpu = kernels.gpu.clone();
        let table = RobinHoodTable {
            kernels: kernels.clone(),
            universe,
            format,
            config,
            cells: CellBuffer::new(&gpu, config.width, table_size)?,
            table_size,
            len: 0,
            report: BuildReport {
                table_size,
                ..BuildReport::default()
            },
        };
        gpu.submit(|rec| {
            table.cells.clear(rec);
            Ok(())
        })?;
        Ok(table)
    }

    /// Clears the cells and inserts `keys[..n]` (unique, inside the universe), growing the
    /// table while an age overflows.
    fn fill_checked(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> Result<(), HashError> {
        let gpu = self.kernels.gpu.clone();
        for _ in 0..8 {
            let counters = GpuBuffer::<u32>::zeroed(&gpu, "robin hood counters", 4)?;
            gpu.submit(|rec| {
                self.cells.clear(rec);
                self.record_insert(rec, keys, payloads, n, &counters)
            })?;
            let c = counters.read()?;
            if c[0] == 0 && c[1] == 0 {
                self.len = n as u64;
                return self.finish();
            }
            let lf = n as f64 / self.table_size as f64;
            self.table_size = table_size_for(n as u64, lf / 1.05)?.max(self.table_size + 2);
            self.cells = CellBuffer::new(&gpu, self.config.width, self.table_size)?;
        }
        Err(HashError::AgeOverflow {
            failed: n as u32,
            max_age: HASH_MAX_AGE,
            load_factor: n as f64 / self.table_size as f64,
            table_size: self.table_size,
        })
    }

    /// Scratch of a recorded insert of up to `n` keys: the table's backup, the counters and
    /// the max-age table.
    ///
    /// # Errors
    /// An allocation failure.
    pub fn append_scratch(&self) -> GpuResult<AppendScratch> {
        let gpu = &self.kernels.gpu;
        Ok(AppendScratch {
            backup: CellBuffer::new(gpu, self.config.width, self.table_size)?,
            counters: GpuBuffer::new(gpu, "robin hood append counters", 4)?,
            mat: GpuBuffer::new(gpu, "robin hood max-age table", self.table_size as usize)?,
            ages: GpuBuffer::new(gpu, "unused", 1)?,
        })
    }

    /// Records the insert of `keys[..n]` → `payloads[..n]` into a submission the caller makes
    /// with other work, for callers that keep their counts on the device: the keys must be new
    /// and unique (not checked), and [`RobinHoodTable::reserve`] must have made room for them.
    /// The table is backed up first; [`RobinHoodTable::finish_append`] after the submission
    /// says whether every key found a cell, and restores the backup when one did not.
    ///
    /// # Errors
    /// Scratch of another size than this table's, or a recording failure.
    pub fn record_append(
        &self,
        rec: &mut Recorder<'_>,
        scratch: &AppendScratch,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> GpuResult<()> {
        crate::prims::check_len("hash keys", n, keys.len().min(payloads.len()))?;
        if scratch.mat.len() != self.table_size as usize {
            return Err(GpuError::InvalidArgument(format!(
                "append scratch for {} cells, table of {}",
                scratch.mat.len(),
                self.table_size
            )));
        }
        rec.fill(&scratch.counters, 0);
        self.cells.copy_to(rec, &scratch.backup)?;
        self.record_set_ages(rec, &scratch.ages, 1)?;
        self.record_insert(rec, keys, payloads, n, &scratch.counters)?;
        self.record_max_age(rec, &scratch.mat, None)?;
        self.record_set_ages(rec, &scratch.mat, 0)
    }

    /// After the submission of [`RobinHoodTable::record_append`] of `n` keys: `true` when every
    /// key was inserted, `false` when an age overflowed or a key was present, in which case the
    /// table is as it was before (from the backup) and the caller inserts again with
    /// [`RobinHoodTable::insert`], which grows the table.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn finish_append(&mut self, scratch: AppendScratch, n: usize) -> Result<bool, HashError> {
        let c = scratch.counters.read()?;
        if c[0] > 0 || c[1] > 0 {
            self.cells = scratch.backup;
            return Ok(false);
        }
        self.len += n as u64;
        self.report.keys = self.len;
        self.report.table_size = self.table_size;
        self.report.load_factor = self.len as f64 / self.table_size as f64;
        self.report.rebuilds.clear();
        Ok(true)
    }

    /// Inserts a further batch `keys[..n]` → `payloads[..n]` (lazy synthesis adds texels as cuts
    /// appear). Past `max_load_factor`, or when an age would overflow, the table is rebuilt
    /// larger when `grow` is set (reported) and the call fails otherwise, leaving the table as
    /// it was.
    pub fn insert(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
    ) -> Result<&BuildReport, HashError> {
        crate::prims::check_len("hash keys", n, keys.len().min(payloads.len()))?;
        let gpu = self.kernels.gpu.clone();
        if self.config.validate {
            Self::validate(
                &self.kernels,
                &self.universe,
                &self.format,
                keys,
                payloads,
                n,
            )?;
            // New keys must not be in the table already.
            let results = GpuBuffer::<u32>::new(&gpu, "insert duplicate check", n)?;
            gpu.submit(|rec| self.record_query(rec, keys, &results, n))?;
            if let Some(i) = results
                .read()?
                .iter()
                .position(|&r| r != crate::shader_constants::HASH_NOT_FOUND)
            {
                let key = keys.read_range(i, 1)?[0];
                return Err(HashError::DuplicateKey { key, count: 1 });
            }
        }
        let total = self.len + n as u64;
        let load = total as f64 / self.table_size as f64;
        if load > self.config.max_load_factor {
            if !self.config.grow {
                return Err(HashError::TableFull {
                    keys: total,
                    capacity: self.table_size as u64,
                    load,
                    max_load_factor: self.config.max_load_factor,
                });
            }
            let reason = format!(
                "{total} keys would reach load factor {load:.4} > {} in {} cells",
                self.config.max_load_factor, self.table_size
            );
            return self.rebuild_with(keys, payloads, n, reason);
        }
        let backup = CellBuffer::new(&gpu, self.config.width, self.table_size)?;
        let counters = GpuBuffer::<u32>::zeroed(&gpu, "robin hood counters", 4)?;
        let ages = GpuBuffer::<u32>::new(&gpu, "unused", 1)?;
        gpu.submit(|rec| {
            self.cells.copy_to(rec, &backup)?;
            self.record_set_ages(rec, &ages, 1)?;
            self.record_insert(rec, keys, payloads, n, &counters)
        })?;
        let c = counters.read()?;
        if c[0] > 0 || c[1] > 0 {
            self.cells = backup;
            if c[1] > 0 {
                return Err(HashError::DuplicateKey {
                    key: 0,
                    count: c[1] as u64,
                });
            }
            let lf = total as f64 / self.table_size as f64;
            if !self.config.grow {
                return Err(HashError::AgeOverflow {
                    failed: c[0],
                    max_age: HASH_MAX_AGE,
                    load_factor: lf,
                    table_size: self.table_size,
                });
            }
            let reason = format!(
                "{} key(s) exceeded age {HASH_MAX_AGE} at load factor {lf:.4} in {} cells",
                c[0], self.table_size
            );
            return self.rebuild_with(keys, payloads, n, reason);
        }
        self.len = total;
        self.finish()?;
        self.report.rebuilds.clear();
        Ok(&self.report)
    }

    /// Rebuilds with every entry present plus `keys[..n]` → `payloads[..n]`, at the configured
    /// load factor, and says why in the report.
    fn rebuild_with(
        &mut self,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        reason: String,
    ) -> Result<&BuildReport, HashError> {
        let (mut all_keys, mut all_payloads) = self.entries()?;
        all_keys.extend(keys.read_range(0, n)?);
        all_payloads.extend(payloads.read_range(0, n)?);
        let validate = self.config.validate;
        let config = RobinHoodConfig {
            validate: false,
            ..self.config
        };
        let rebuilt = RobinHoodTable::build_from_slices(
            &self.kernels,
            self.universe,
            &all_keys,
            &all_payloads,
            config,
        )?;
        let mut rebuilds = vec![format!(
            "{reason}; rebuilt with {} cells",
            rebuilt.table_size
        )];
        rebuilds.extend(rebuilt.report.rebuilds.iter().cloned());
        *self = rebuilt;
        // The entries were checked already; later inserts are checked as configured.
        self.config.validate = validate;
        self.report.rebuilds = rebuilds;
        Ok(&self.report)
    }

    /// The (key, payload) pairs in the table, in cell order.
    pub fn entries(&self) -> Result<(Vec<u64>, Vec<u32>), HashError> {
        let f = self.format;
        let cells = self.cells.read()?;
        Ok(cells
            .iter()
            .filter(|&&c| c != 0)
            .map(|&c| (f.key1(c) - 1, f.payload(c)))
            .unzip())
    }

    /// Records `results[i]` = the payload of `keys[i]` or `HASH_NOT_FOUND`, for `i < n`.
    pub fn record_query(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        results: &GpuBuffer<u32>,
        n: usize,
    ) -> GpuResult<()> {
        crate::prims::check_len("hash queries", n, keys.len().min(results.len()))?;
        let k = self.kernels.robin_hood(self.config.width);
        let push = QueryPush {
            cells: self.cells.address(),
            fastmod_m: fastmod_multiplier(self.table_size),
            keys: keys.address(),
            results: results.address(),
            n: n as u32,
            table_size: self.table_size,
            key_bits: self.format.key_bits,
        };
        let query = k.query(&self.kernels.gpu, self.config.probe)?;
        rec.dispatch(&query, query.groups_for(n as u64), &[], &push)
    }

    /// Queries `keys` and reads the results back.
    pub fn query(&self, keys: &[u64]) -> GpuResult<Vec<u32>> {
        self.kernels
            .run_queries(keys, |rec, k, r, n| self.record_query(rec, k, r, n))
    }

    /// The cells (widened to 64 bits), MAT in the age bits.
    pub fn cells(&self) -> GpuResult<Vec<u64>> {
        self.cells.read()
    }

    /// Device address of the cells, for kernels that include `hash/robin_hood_lookup.glsl`.
    pub fn cells_address(&self) -> DeviceAddress<'_> {
        self.cells.address()
    }

    /// Exact GPU bytes of the table (the cells; nothing else stays allocated).
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

    /// The cell layout.
    pub fn format(&self) -> CellFormat {
        self.format
    }

    /// The configuration.
    pub fn config(&self) -> &RobinHoodConfig {
        &self.config
    }

    /// The universe.
    pub fn universe(&self) -> &Universe {
        &self.universe
    }
}
