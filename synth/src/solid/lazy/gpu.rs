//! Lazy synthesis on the GPU. The state of every level lives in the project's coherent hash
//! (a Robin Hood table with the coherent probe sequence, Morton keys of the voxel positions
//! plus [`LAZY_MARGIN`]) whose payload is a slot, and per slot the versions computed so far
//! (`passes + 1` triples) and their count. A chunk of a request runs in three submissions,
//! whatever the number of levels and stages, and the host reads only a few counters between
//! them; the requested keys of [`GpuLazySolid::colours`] never leave the device:
//!
//! 1. the dependency walk (`walk.rs`): per level, finest first, the stage-tagged keys of every
//!    voxel needed, stopping at stored versions, and how many of them are new to the state;
//! 2. every level's lookups (`lazy_prepare.comp`), new slots (`lazy_assign.comp`) and the
//!    inserts of its new voxels into its table, with room made beforehand from the walk's
//!    counts;
//! 3. every level's upsampling of the voxels with no version (`lazy_upsample.comp`) and its
//!    `8 × passes` subpasses (`lazy_correct.comp`, each over its own stretch of the level's
//!    voxels sorted by class, `visit_order.rs`), coarsest first;
//!
//! then the chunk's colours or final triples (`lazy_colours.comp`, `lazy_gather.comp`). The
//! CPU reference is [`LazySolidCpu`](super::LazySolidCpu); both equal the full volume.
//!
//! A voxel costs the table's cell, `12 · (passes + 1)` bytes of versions and 4 bytes of count.
//! What stays between requests is the state's [`MemoryPolicy`] (`policy.rs`): every version,
//! or levels within a byte budget (the finest last, the level past the budget in part),
//! applied after each chunk of
//! [`LAZY_CHUNK_VOXELS`] requested voxels; [`GpuLazySolid::bytes`] reports what is kept.

use super::correct_parts::CorrectParts;
use super::deps::{Dependencies, LevelDeps};
use super::keys::{check_within, lazy_key, untag};
use super::policy::{LevelKeep, MemoryPolicy, LAZY_CHUNK_VOXELS};
use super::visit_order::{StageRanges, VisitOrder};
use super::walk::{texture_key_bits, DeviceWalk, LevelSet, WalkRequest, WalkSets};
use crate::cache::DiskCache;
use crate::kernels::synth_solid;
use crate::shader_constants::{LAZY_ORDER_BITS, LAZY_RANGE_WORDS};
use crate::solid::analysis::{analyze_solid, SolidAnalysis};
use crate::solid::candidates::CandidateParams;
use crate::solid::candidates::SolidCandidates;
use crate::solid::candidates_cache::candidates_cached;
use crate::solid::candidates_host::CandidateBuilder;
use crate::solid::cpu::check_levels;
use crate::solid::defaults::{
    default_solid_jitter, default_solid_passes, DEFAULT_SOLID_PARALLEL_LEVELS,
};
use crate::solid::gpu::GpuSolidSynthesizer;
use crate::solid::relief::{role_texel, SolidRelief};
use crate::solid::roles::{SolidExemplars, ROLES};
use crate::solid::schedule::{level_schedules, LevelSchedule};
use crate::{SynthError, SynthParams, SynthResult};
use lazysolid_compute::gpu::{DeviceAddress, DeviceRecords, Gpu, GpuBuffer, Kernel, PushValue};
use lazysolid_compute::hash::{
    fastmod_multiplier, morton_decode, AppendScratch, HashKernels, KeyLayout, RobinHoodConfig,
    RobinHoodTable, Universe,
};
use lazysolid_compute::prims::{RadixSort, Scan, MAX_ELEMENTS};
use lazysolid_compute::shader_constants::DEFAULT_WORKGROUP_SIZE;
use lazysolid_compute::voxel::VoxelKeys;
use std::sync::Arc;

/// Voxels of room around the requested `[0, R)³` at every level: the dependencies reach at
/// most 5 voxels a side per pass and level along x (3 along y, 2 along z) plus half the
/// reach of the level below, under 80 for the largest pass count.
pub const LAZY_MARGIN: i32 = 96;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct PreparePush<'a> {
        levels: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        slots: DeviceAddress<'a>,
        flags: DeviceAddress<'a>,
        work: DeviceAddress<'a>,
        order_keys: DeviceAddress<'a>,
        order: DeviceAddress<'a>,
        n: u32,
        level: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct AssignPush<'a> {
        levels: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        slots: DeviceAddress<'a>,
        offsets: DeviceAddress<'a>,
        new_keys: DeviceAddress<'a>,
        new_payloads: DeviceAddress<'a>,
        n: u32,
        level: u32,
        base: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LazyUpsamplePush<'a> {
        levels: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        slots: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        n: u32,
        level: u32,
        side: u32,
        spacing: u32,
        seed: u32,
        strength: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct LazyCorrectPush<'a> {
        levels: DeviceAddress<'a>,
        table: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        order: DeviceAddress<'a>,
        ranges: DeviceAddress<'a>,
        slots: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        level: u32,
        stage: u32,
        cls: u32,
        version: u32,
        side: u32,
        spacing: u32,
        keep_current: u32,
        seed: u32,
        strength: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct GatherPush<'a> {
        levels: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        triples: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        n: u32,
        level: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ColoursPush<'a> {
        levels: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        rgb: DeviceAddress<'a>,
        colours: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        n: u32,
        level: u32,
        side: u32,
    }
}

lazysolid_compute::push_block! {
    /// One level as the kernels see it: `LazyLevel` in `glsl/include/synth/lazy.glsl`,
    /// borrowing the level's table, versions and counts.
    #[derive(Clone, Copy)]
    pub(crate) struct LazyLevelRecord<'a> {
        cells: DeviceAddress<'a>,
        fastmod_m: u64,
        versions: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        table_size: u32,
        key_bits: u32,
        probe: u32,
        stride: u32,
        margin: i32,
        extent: u32,
        parallel: u32,
    }
}

/// One level's state.
struct LevelState {
    universe: Universe,
    table: Option<RobinHoodTable>,
    versions: GpuBuffer<u32>,
    counts: GpuBuffer<u32>,
    stride: u32,
    len: u32,
    schedule: LevelSchedule,
}

impl LevelState {
    fn record(&self) -> LazyLevelRecord<'_> {
        let (cells, table_size, key_bits, probe) = match &self.table {
            Some(t) => (
                t.cells_address(),
                t.table_size(),
                t.format().key_bits,
                t.config().probe.id(),
            ),
            None => (DeviceAddress::NULL, 0, 0, 0),
        };
        LazyLevelRecord {
            cells,
            fastmod_m: fastmod_multiplier(table_size.max(1)),
            versions: self.versions.address(),
            counts: self.counts.address(),
            table_size,
            key_bits,
            probe,
            stride: self.stride,
            margin: LAZY_MARGIN,
            extent: self.universe.dims[0],
            parallel: self.schedule.parallel as u32,
        }
    }

    /// Forgets every voxel of level `l` (the memory policy), back to the initial buffers.
    fn clear(&mut self, gpu: &Gpu, l: usize) -> SynthResult<()> {
        self.table = None;
        self.versions = GpuBuffer::zeroed(
            gpu,
            format!("lazy versions level {l}"),
            INITIAL_SLOTS * 3 * self.stride as usize,
        )?;
        self.counts = GpuBuffer::zeroed(gpu, format!("lazy counts level {l}"), INITIAL_SLOTS)?;
        self.len = 0;
        Ok(())
    }

    fn bytes(&self) -> u64 {
        self.table.as_ref().map_or(0, |t| t.bytes()) + self.versions.bytes() + self.counts.bytes()
    }

    /// Slots the versions and counts would be fitted to (the voxels held, rounded up to
    /// [`INITIAL_SLOTS`]), when they hold more than an eighth spare.
    fn fitted_slots(&self) -> Option<usize> {
        let fitted = (self.len as usize).div_ceil(INITIAL_SLOTS).max(1) * INITIAL_SLOTS;
        (self.counts.len() > fitted + fitted / 8).then_some(fitted)
    }

    /// [`LevelState::bytes`] once fitted ([`LevelState::fitted_slots`]).
    fn fitted_bytes(&self) -> u64 {
        match self.fitted_slots() {
            Some(slots) => {
                let per_slot = self.versions.bytes() / self.counts.len() as u64 + 4;
                self.table.as_ref().map_or(0, |t| t.bytes()) + per_slot * slots as u64
            }
            None => self.bytes(),
        }
    }
}

/// What a lazy state is made with besides its exemplars and resolution: the seed, and
/// overrides of the synthesizer's defaults (`None`: the default).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LazyOptions {
    /// Seed of the jitter.
    pub seed: u32,
    /// Finest levels corrected in parallel passes (`SynthParams::parallel_levels`).
    pub parallel_levels: Option<u32>,
    /// What the state keeps between requests.
    pub policy: Option<MemoryPolicy>,
    /// Whether the texels carry the relief channel in alpha (`crate::relief`).
    pub relief: bool,
}

impl LazyOptions {
    /// The defaults with `seed`.
    pub fn new(seed: u32) -> LazyOptions {
        LazyOptions {
            seed,
            parallel_levels: None,
            policy: None,
            relief: false,
        }
    }
}

/// What one request did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LazyReport {
    /// Voxels in each level's dependency set, coarsest first.
    pub needed: Vec<u64>,
    /// Voxel versions computed at each level (upsampled or corrected), coarsest first.
    pub computed: Vec<u64>,
    /// Voxels new to the state at each level (each upsampled once; the rest of `computed`
    /// are corrections), coarsest first.
    pub upsampled: Vec<u64>,
    /// Device time of the synthesis kernels, milliseconds.
    pub gpu_ms: f64,
    /// Wall time of the dependency walk, milliseconds.
    pub deps_ms: f64,
    /// Wall time of the whole request, milliseconds.
    pub wall_ms: f64,
    /// Chunks the request ran in (`policy.rs`).
    pub chunks: u32,
    /// The largest state alive during the request, before the policy applied (bytes).
    pub peak_state_bytes: u64,
    /// Levels the policy emptied or cut back after the request's last chunk.
    pub dropped_levels: u32,
    /// Dependency walks run: one per chunk, and one more for each walk whose sets outgrew
    /// the walk's buffers (`walk.rs`).
    pub walks: u32,
    /// Submissions the host waited for during the request (the policy's included).
    pub waits: u64,
    /// Level hash tables made, rebuilt larger or refilled after an age overflowed: the
    /// waits a request adds to its fixed few per chunk, besides retried walks.
    pub table_growths: u32,
}

impl LazyReport {
    /// Adds one chunk's report to this one.
    fn add(&mut self, chunk: &LazyReport) {
        let sum = |a: &mut Vec<u64>, b: &[u64]| {
            a.resize(a.len().max(b.len()), 0);
            for (x, y) in a.iter_mut().zip(b) {
                *x += y;
            }
        };
        sum(&mut self.needed, &chunk.needed);
        sum(&mut self.computed, &chunk.computed);
        sum(&mut self.upsampled, &chunk.upsampled);
        self.gpu_ms += chunk.gpu_ms;
        self.deps_ms += chunk.deps_ms;
        self.chunks += 1;
        self.walks += chunk.walks;
        self.waits += chunk.waits;
        self.table_growths += chunk.table_growths;
        self.peak_state_bytes = self.peak_state_bytes.max(chunk.peak_state_bytes);
    }
}

/// Lazy synthesis of one volume texture of resolution `R` (finest-level voxels `[0, R)³`) on
/// the GPU, keeping its state between requests.
pub struct GpuLazySolid {
    gpu: Gpu,
    synth: GpuSolidSynthesizer,
    hash: Arc<HashKernels>,
    scan: Scan,
    prepare: Arc<Kernel>,
    assign: Arc<Kernel>,
    upsample: Arc<Kernel>,
    correct: Arc<Kernel>,
    stage_ranges: StageRanges,
    gather: Arc<Kernel>,
    colour: Arc<Kernel>,
    walk: DeviceWalk,
    sort: RadixSort,
    params: SynthParams,
    resolution: u32,
    levels: Vec<LevelState>,
    /// Every level's record, rewritten whenever a level's table or buffers change.
    records: DeviceRecords,
    /// Every role's exemplar texels (`role_texel`: RGB and the relief code or 255), role
    /// after role.
    rgb: GpuBuffer<u32>,
    /// The relief the texels carry.
    relief: Option<SolidRelief>,
    /// What stays between requests.
    policy: MemoryPolicy,
    /// Requested voxels synthesized together before the policy applies.
    chunk_voxels: usize,
    /// What the last request did (`GpuLazySolid::last_report`).
    last: LazyReport,
    /// The order the correction visits a level's voxels in.
    visit: VisitOrder,
}

/// What a chunked request does with each chunk while its final versions are stored:
/// `(state, index of the chunk's first key, the chunk's length)`.
type ChunkExtract<'a> = dyn FnMut(&mut GpuLazySolid, usize, usize) -> SynthResult<()> + 'a;

/// A level's versions and counts before they moved into larger buffers, and how many voxels
/// they hold: what the move copies.
struct MovedLevel {
    l: usize,
    versions: GpuBuffer<u32>,
    counts: GpuBuffer<u32>,
    used: usize,
}

/// One level's buffers while a chunk synthesizes it (`GpuLazySolid::synthesize_levels`).
struct LevelWork {
    l: usize,
    /// Voxels of the level's set, and how many of them are new to its state.
    n: usize,
    fresh: usize,
    /// The level's voxels before the chunk: the first new voxel's slot.
    base: u32,
    slots: GpuBuffer<u32>,
    flags: GpuBuffer<u32>,
    /// The lookups' count of new voxels and of versions to compute.
    totals: GpuBuffer<u32>,
    order_keys: GpuBuffer<u32>,
    order: GpuBuffer<u32>,
    new_keys: GpuBuffer<u64>,
    new_payloads: GpuBuffer<u32>,
    /// The recorded insert's scratch, when the level has new voxels.
    append: Option<AppendScratch>,
    errors: GpuBuffer<u32>,
    ranges: GpuBuffer<u32>,
}

/// The voxels of a chunked request.
#[derive(Clone, Copy)]
enum Requested<'a> {
    /// Lazy keys on the host, in the caller's order (each chunk is walked sorted).
    Host(&'a [u64]),
    /// Sorted unique Morton keys of texture positions on the device, which stay there.
    Device(&'a VoxelKeys),
}

impl Requested<'_> {
    fn len(&self) -> usize {
        match self {
            Requested::Host(keys) => keys.len(),
            Requested::Device(keys) => keys.len(),
        }
    }
}

/// The specialization constant of `lazy_correct.comp` that selects its parts (`PARTS`).
const CORRECT_PARTS_ID: u32 = 1;

/// Initial slots per level.
const INITIAL_SLOTS: usize = 1024;

impl GpuLazySolid {
    /// Uploads the analysis and candidates for textures of `resolution`³ voxels synthesized
    /// with `params`.
    ///
    /// # Errors
    /// Parameters that do not fit the analysis, a resolution outside 1..=4096, or a GPU
    /// failure.
    pub fn new(
        gpu: &Gpu,
        exemplars: &SolidExemplars,
        analysis: &SolidAnalysis,
        candidates: &SolidCandidates,
        params: &SynthParams,
        resolution: u32,
    ) -> SynthResult<GpuLazySolid> {
        check_levels(analysis, candidates, params)?;
        if !(1..=4096).contains(&resolution) {
            return Err(SynthError::Parameter {
                name: "resolution",
                value: resolution.to_string(),
                limit: "must lie in 1..=4096".into(),
            });
        }
        let n_levels = analysis.levels.len();
        let schedules = level_schedules(params);
        let mut levels = Vec::with_capacity(n_levels);
        for (l, &schedule) in schedules.iter().enumerate() {
            let shift = (n_levels - 1 - l) as u32;
            let extent = resolution.div_ceil(1 << shift) + 2 * LAZY_MARGIN as u32;
            let universe = Universe::new_3d([extent; 3], KeyLayout::Morton).map_err(|e| {
                SynthError::Parameter {
                    name: "resolution",
                    value: resolution.to_string(),
                    limit: e.to_string(),
                }
            })?;
            let stride = params.passes[l] + 1;
            levels.push(LevelState {
                universe,
                table: None,
                versions: GpuBuffer::zeroed(
                    gpu,
                    format!("lazy versions level {l}"),
                    INITIAL_SLOTS * 3 * stride as usize,
                )?,
                counts: GpuBuffer::zeroed(gpu, format!("lazy counts level {l}"), INITIAL_SLOTS)?,
                stride,
                len: 0,
                schedule,
            });
        }
        let records: Vec<LazyLevelRecord<'_>> = levels.iter().map(LevelState::record).collect();
        let records = DeviceRecords::new(gpu, "lazy level records", &records)?;
        let rgb = role_texels(exemplars, None);
        let me = GpuLazySolid {
            gpu: gpu.clone(),
            synth: GpuSolidSynthesizer::new(gpu, analysis, candidates)?,
            hash: HashKernels::new(gpu)?,
            scan: Scan::new(gpu)?,
            prepare: gpu.kernel(&synth_solid::LAZY_PREPARE)?,
            assign: gpu.kernel(&synth_solid::LAZY_ASSIGN)?,
            upsample: gpu.kernel(&synth_solid::LAZY_UPSAMPLE)?,
            correct: gpu.kernel(&synth_solid::LAZY_CORRECT)?,
            stage_ranges: StageRanges::new(gpu)?,
            gather: gpu.kernel(&synth_solid::LAZY_GATHER)?,
            colour: gpu.kernel(&synth_solid::LAZY_COLOURS)?,
            walk: DeviceWalk::new(gpu, n_levels)?,
            sort: RadixSort::new(gpu)?,
            params: params.clone(),
            resolution,
            levels,
            records,
            rgb: GpuBuffer::from_slice(gpu, "lazy exemplar colours", &rgb)?,
            relief: None,
            policy: MemoryPolicy::default(),
            chunk_voxels: LAZY_CHUNK_VOXELS,
            last: LazyReport::default(),
            visit: VisitOrder::default(),
        };
        Ok(me)
    }

    /// Whether texels from now on carry `relief` in their alpha byte (`None`: alpha 255), for
    /// the images of `exemplars` (those the state was made with). Voxels already returned
    /// keep what they were given: set it before the first request.
    ///
    /// # Errors
    /// Device errors (uploading the exemplars' texels).
    pub fn set_relief(
        &mut self,
        exemplars: &SolidExemplars,
        relief: Option<SolidRelief>,
    ) -> SynthResult<()> {
        let texels = role_texels(exemplars, relief.as_ref());
        self.rgb = GpuBuffer::from_slice(&self.gpu, "lazy exemplar colours", &texels)?;
        self.relief = relief;
        Ok(())
    }

    /// The relief the texels carry, if any.
    pub fn relief(&self) -> Option<&SolidRelief> {
        self.relief.as_ref()
    }

    /// How much of the correction runs from now on: [`CorrectParts::All`] (the default) except
    /// in a profile of its parts, where the state's later versions are wrong.
    ///
    /// # Errors
    /// Pipeline creation failures.
    pub fn set_correct_parts(&mut self, parts: CorrectParts) -> SynthResult<()> {
        self.correct = match parts {
            CorrectParts::All => self.gpu.kernel(&synth_solid::LAZY_CORRECT)?,
            part => self.gpu.kernel_with(
                &synth_solid::LAZY_CORRECT,
                DEFAULT_WORKGROUP_SIZE,
                &[(CORRECT_PARTS_ID, part.constant())],
            )?,
        };
        Ok(())
    }

    /// Sets the order the correction visits a level's voxels in (a profile's comparison;
    /// the versions are the same).
    pub fn set_visit_order(&mut self, visit: VisitOrder) {
        self.visit = visit;
    }

    /// What the state keeps between requests from now on (applied after the next chunk).
    pub fn set_policy(&mut self, policy: MemoryPolicy) {
        self.policy = policy;
    }

    /// What the state keeps between requests.
    pub fn policy(&self) -> MemoryPolicy {
        self.policy
    }

    /// Requested voxels synthesized together before the policy applies (at least 1; the
    /// default is [`LAZY_CHUNK_VOXELS`]; tests use small chunks to exercise the policy).
    pub fn set_chunk_voxels(&mut self, voxels: usize) {
        self.chunk_voxels = voxels.max(1);
    }

    /// Empties the levels the policy does not keep, cuts back the one it keeps in part, and
    /// fits the others' versions to the voxels they hold (the policy weighs what is kept,
    /// not what a request grew it to); returns how many levels that held voxels were emptied
    /// or cut back.
    fn apply_policy(&mut self, last: bool) -> SynthResult<u32> {
        // The budget weighs each level as fitted; only the levels it keeps whole are fitted
        // (one kept in part is rebuilt, one emptied freed), after the request's last chunk
        // (between chunks the levels keep the room they grew, which the next chunk uses),
        // all in one submission.
        let fits = self.policy != MemoryPolicy::Keep;
        let mut moves = Vec::new();
        let bytes: Vec<u64> = if fits {
            self.levels.iter().map(LevelState::fitted_bytes).collect()
        } else {
            self.levels.iter().map(LevelState::bytes).collect()
        };
        let mut changed = false;
        let mut dropped = 0;
        for (l, keep) in self.policy.plan(&bytes).into_iter().enumerate() {
            if self.levels[l].len == 0 {
                continue;
            }
            match keep {
                LevelKeep::All => {
                    if fits && last {
                        if let Some(fitted) = self.levels[l].fitted_slots() {
                            moves.push(self.resize_later(l, fitted)?);
                            changed = true;
                        }
                    }
                }
                LevelKeep::Part(bytes) => {
                    self.keep_part(l, bytes)?;
                    dropped += 1;
                }
                LevelKeep::Nothing => {
                    self.levels[l].clear(&self.gpu, l)?;
                    dropped += 1;
                }
            }
        }
        if !moves.is_empty() {
            self.gpu.submit(|rec| {
                for m in &moves {
                    self.record_move(rec, m)?;
                }
                Ok(())
            })?;
        }
        if dropped > 0 || changed {
            self.write_records()?;
        }
        Ok(dropped)
    }

    /// Keeps of level `l` the voxels that fit in `bytes` (table, versions and counts), the
    /// first ones in Morton order, a region of the level; the rest are recomputed where a
    /// later request needs them.
    fn keep_part(&mut self, l: usize, bytes: u64) -> SynthResult<()> {
        let state = &self.levels[l];
        let Some(table) = &state.table else {
            return Ok(());
        };
        let words = 3 * state.stride as usize;
        // A kept voxel's bytes: its versions and count, and its share of the table's cells at
        // the load factor a table is built at; the fitted buffers round up to INITIAL_SLOTS.
        let cell = table.bytes() as f64 / f64::from(table.table_size().max(1));
        let per_voxel = (4 * words + 4) as f64 + cell / table.config().load_factor;
        let estimate = ((bytes as f64 - 2.0 * cell) / per_voxel).max(0.0) as usize;
        let mut keep = estimate
            .saturating_sub(INITIAL_SLOTS)
            .min(state.len as usize);
        let (keys, slots) = table.entries().map_err(|e| hash_error(l, e))?;
        // The table's keys are Morton codes (`lazy_table_key`): the first ones are a region.
        let mut pairs: Vec<(u64, u32)> = keys.into_iter().zip(slots).collect();
        pairs.sort_unstable();
        let (versions, counts) = (state.versions.read()?, state.counts.read()?);
        let universe = state.universe;
        let config = RobinHoodConfig {
            validate: true,
            ..RobinHoodConfig::default()
        };
        // The estimate is checked against the bytes built; past them, fewer voxels.
        while keep > 0 {
            let slots = keep.div_ceil(INITIAL_SLOTS) * INITIAL_SLOTS;
            let mut kept_versions = vec![0u32; slots * words];
            let mut kept_counts = vec![0u32; slots];
            for (i, &(_, s)) in pairs[..keep].iter().enumerate() {
                let s = s as usize;
                kept_versions[i * words..(i + 1) * words]
                    .copy_from_slice(&versions[s * words..(s + 1) * words]);
                kept_counts[i] = counts[s];
            }
            let keys: Vec<u64> = pairs[..keep].iter().map(|p| p.0).collect();
            let payloads: Vec<u32> = (0..keep as u32).collect();
            let table =
                RobinHoodTable::build_from_slices(&self.hash, universe, &keys, &payloads, config)
                    .map_err(|e| hash_error(l, e))?;
            let built = table.bytes() + 4 * (kept_versions.len() + kept_counts.len()) as u64;
            if built > bytes {
                keep = (keep as f64 * bytes as f64 / built as f64 * 0.98) as usize;
                continue;
            }
            let gpu = &self.gpu;
            let state = &mut self.levels[l];
            state.versions =
                GpuBuffer::from_slice(gpu, format!("lazy versions level {l}"), &kept_versions)?;
            state.counts =
                GpuBuffer::from_slice(gpu, format!("lazy counts level {l}"), &kept_counts)?;
            state.table = Some(table);
            state.len = keep as u32;
            return Ok(());
        }
        self.levels[l].clear(&self.gpu, l)
    }

    /// The keys ([`lazy_key`]) of the voxels level `l` holds, in increasing order: what a
    /// policy kept, for tests and reports.
    ///
    /// # Errors
    /// A level past the finest, or a failed read.
    pub fn stored_keys(&self, l: usize) -> SynthResult<Vec<u64>> {
        let state = self.levels.get(l).ok_or_else(|| SynthError::Parameter {
            name: "lazy level",
            value: l.to_string(),
            limit: format!("below {}", self.levels.len()),
        })?;
        // The table's keys are Morton codes of the position plus the margin
        // (`lazy_table_key` in `lazy.glsl`).
        let mut keys: Vec<u64> = match &state.table {
            Some(t) => t.entries().map_err(|e| hash_error(l, e))?.0,
            None => Vec::new(),
        }
        .into_iter()
        .map(|k| lazy_key(morton_decode(k, 3).map(|c| c as i32 - LAZY_MARGIN)))
        .collect();
        keys.sort_unstable();
        Ok(keys)
    }

    /// Runs `requested` (in the order given) in chunks of
    /// [`GpuLazySolid::set_chunk_voxels`]: per chunk the dependency walk and every level's
    /// synthesis, then `extract(self, first, len)` while the chunk's final versions are stored,
    /// then the policy.
    fn run_chunks(
        &mut self,
        requested: Requested<'_>,
        extract: &mut ChunkExtract<'_>,
    ) -> SynthResult<LazyReport> {
        let total = requested.len();
        let mut report = LazyReport::default();
        let mut first = 0;
        loop {
            let len = self.chunk_voxels.min(total - first);
            let start = std::time::Instant::now();
            let before = self.gpu.submissions();
            let host_keys;
            let walk = match requested {
                Requested::Host(keys) => {
                    let mut sorted = keys[first..first + len].to_vec();
                    sorted.sort_unstable();
                    sorted.dedup();
                    host_keys = (!sorted.is_empty())
                        .then(|| GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &sorted))
                        .transpose()?;
                    WalkRequest {
                        keys: host_keys
                            .as_ref()
                            .map_or(DeviceAddress::NULL, GpuBuffer::address),
                        n: sorted.len(),
                        or_bits: 0,
                        resolution: 0,
                    }
                }
                Requested::Device(keys) => WalkRequest {
                    keys: if len == 0 {
                        DeviceAddress::NULL
                    } else {
                        keys.keys.address_at(first)?
                    },
                    n: len,
                    or_bits: texture_key_bits(),
                    resolution: self.resolution,
                },
            };
            let mut r = self.synthesize(walk, start)?;
            r.peak_state_bytes = self.bytes() + self.walk.bytes();
            if len > 0 {
                extract(self, first, len)?;
            }
            report.dropped_levels = self.apply_policy(first + len >= total)?;
            r.waits = self.gpu.submissions().since(before).waits;
            report.add(&r);
            first += len;
            if first >= total {
                break;
            }
        }
        self.walk.release();
        Ok(report)
    }

    /// The lazy state of `exemplars` at `resolution` with the solid synthesizer's defaults and
    /// `seed`: the analysis, and the candidates through `cache` (computed on the GPU on a
    /// miss). How scenes make one.
    ///
    /// # Errors
    /// As [`GpuLazySolid::new`], and candidate or cache failures.
    pub fn with_defaults(
        gpu: &Gpu,
        exemplars: &SolidExemplars,
        seed: u32,
        resolution: u32,
        cache: Option<&DiskCache>,
    ) -> SynthResult<GpuLazySolid> {
        GpuLazySolid::with_options(gpu, exemplars, &LazyOptions::new(seed), resolution, cache)
    }

    /// As [`GpuLazySolid::with_defaults`], with `options` overriding them (how `bench lazy`
    /// and `bench cuts` measure the alternatives).
    ///
    /// # Errors
    /// As [`GpuLazySolid::with_defaults`], and options that do not fit the pyramid.
    pub fn with_options(
        gpu: &Gpu,
        exemplars: &SolidExemplars,
        options: &LazyOptions,
        resolution: u32,
        cache: Option<&DiskCache>,
    ) -> SynthResult<GpuLazySolid> {
        let analysis = analyze_solid(exemplars);
        let params = CandidateParams::default();
        let (candidates, _) = candidates_cached(exemplars, &params, cache, || {
            // The same candidates on either side; natively on the host on a CPU device.
            CandidateBuilder::Auto.compute(gpu, &analysis, &params, &mut |_| {})
        })?;
        let levels = analysis.levels.len() as u32;
        let synth = SynthParams::new(
            levels,
            options.seed,
            &default_solid_passes(levels),
            &default_solid_jitter(levels),
        )?
        .with_parallel_levels(
            options
                .parallel_levels
                .unwrap_or(DEFAULT_SOLID_PARALLEL_LEVELS.min(levels)),
        )?;
        let mut state =
            GpuLazySolid::new(gpu, exemplars, &analysis, &candidates, &synth, resolution)?;
        state.set_policy(options.policy.unwrap_or_default());
        if options.relief {
            state.set_relief(exemplars, Some(SolidRelief::of(exemplars)))?;
        }
        Ok(state)
    }

    /// Rewrites the records the kernels read (they keep the buffers they point into alive).
    fn write_records(&mut self) -> SynthResult<()> {
        let records: Vec<LazyLevelRecord<'_>> =
            self.levels.iter().map(LevelState::record).collect();
        self.records = DeviceRecords::new(&self.gpu, "lazy level records", &records)?;
        Ok(())
    }

    /// Forgets what the dependency walk learned about the size of its sets, so that the next
    /// walks start from the smallest buffers and run again each time a set outgrows one: the
    /// tests' way to check that a retried walk equals the reference.
    #[doc(hidden)]
    pub fn start_walk_small(&mut self) {
        self.walk.start_small();
    }

    /// What the last [`GpuLazySolid::colours`] request did, per level: for callers that see
    /// only a summary of it (a store that grows by a cut), such as `bench cuts`' per-level
    /// notes of what a cut recomputes.
    pub fn last_report(&self) -> &LazyReport {
        &self.last
    }

    /// Bytes of the kept state: tables, versions and counts of every level.
    pub fn bytes(&self) -> u64 {
        let record = <LazyLevelRecord<'_> as PushValue>::SIZE as u64;
        self.levels.iter().map(LevelState::bytes).sum::<u64>() + record * self.levels.len() as u64
    }

    /// Bytes of the kept state per level, coarsest first.
    pub fn level_bytes(&self) -> Vec<u64> {
        self.levels.iter().map(LevelState::bytes).collect()
    }

    /// Voxels stored per level, coarsest first.
    pub fn stored(&self) -> Vec<u64> {
        self.levels.iter().map(|l| l.len as u64).collect()
    }

    /// The dependency sets of the finest-level voxels `requested` given what is stored,
    /// walked on the GPU and read back (what [`dependencies_cpu`](super::dependencies_cpu)
    /// computes from the same stored versions).
    ///
    /// # Errors
    /// As [`GpuLazySolid::request`].
    pub fn dependencies(&mut self, requested: &[[i32; 3]]) -> SynthResult<Dependencies> {
        self.check_requested(requested)?;
        let mut keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
        keys.sort_unstable();
        keys.dedup();
        let buffer = (!keys.is_empty())
            .then(|| GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &keys))
            .transpose()?;
        let request = WalkRequest {
            keys: buffer
                .as_ref()
                .map_or(DeviceAddress::NULL, GpuBuffer::address),
            n: keys.len(),
            or_bits: 0,
            resolution: 0,
        };
        let walked = self.walk(request)?;
        let mut levels = Vec::with_capacity(walked.sets.len());
        for set in &walked.sets {
            let tagged = if set.len == 0 {
                Vec::new()
            } else {
                set.tagged.read_range(0, set.len)?
            };
            levels.push(LevelDeps {
                keys: tagged.iter().map(|&t| untag(t).0).collect(),
                need: tagged.iter().map(|&t| untag(t).1 as u8).collect(),
            });
        }
        self.walk.give_back(walked.sets);
        self.walk.release();
        Ok(levels.into())
    }

    fn check_requested(&self, requested: &[[i32; 3]]) -> SynthResult<()> {
        let r = self.resolution as i32;
        let limit = format!("must lie in 0..{r} (the texture's resolution)");
        for &p in requested {
            check_within(p, 0..r, &limit)?;
        }
        self.check_count(requested.len())
    }

    /// Refuses a request of more voxels than one walk may hold.
    fn check_count(&self, n: usize) -> SynthResult<()> {
        if n > MAX_ELEMENTS / 8 {
            return Err(SynthError::Parameter {
                name: "requested voxels",
                value: n.to_string(),
                limit: format!(
                    "at most {} per request (split the request)",
                    MAX_ELEMENTS / 8
                ),
            });
        }
        Ok(())
    }

    /// Synthesizes the voxels `keys` (sorted Morton keys of positions in the `R³` grid: a
    /// mesh's surface or interpolation voxels, a cut's) and returns their RGBA8 colours on the
    /// device in key order, ready as a
    /// [`ColourSource::Buffer`](lazysolid_compute::store::ColourSource::Buffer) for any store.
    ///
    /// # Errors
    /// As [`GpuLazySolid::request`].
    pub fn colours(&mut self, keys: &VoxelKeys) -> SynthResult<(GpuBuffer<u32>, LazyReport)> {
        let start = std::time::Instant::now();
        let n = keys.len();
        self.check_count(n)?;
        let colours = GpuBuffer::<u32>::new(&self.gpu, "lazy colours", n.max(1))?;
        let errors = GpuBuffer::<u32>::new(&self.gpu, "lazy colour errors", 1)?;
        let mut report = self.run_chunks(Requested::Device(keys), &mut |me, first, len| {
            let push = ColoursPush {
                levels: me.records.address(),
                keys: keys.keys.address_at(first)?,
                rgb: me.rgb.address(),
                colours: colours.address_at(first)?,
                errors: errors.address(),
                n: len as u32,
                level: (me.levels.len() - 1) as u32,
                side: me.synth.side(),
            };
            me.gpu.submit(|rec| {
                if first == 0 {
                    rec.fill(&errors, 0);
                }
                rec.dispatch(&me.colour, me.colour.groups_for(len as u64), &[], &push)
            })?;
            Ok(())
        })?;
        check_errors(&errors, "voxels missing or not final")?;
        report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
        self.last = report.clone();
        Ok((colours, report))
    }

    /// The dependency walk and the synthesis of every level for `request`.
    fn synthesize(
        &mut self,
        request: WalkRequest<'_>,
        start: std::time::Instant,
    ) -> SynthResult<LazyReport> {
        if request.n == 0 {
            let zeros = vec![0; self.levels.len()];
            return Ok(LazyReport {
                needed: zeros.clone(),
                computed: zeros.clone(),
                upsampled: zeros,
                ..LazyReport::default()
            });
        }
        let walked = self.walk(request)?;
        let mut report = LazyReport {
            deps_ms: start.elapsed().as_secs_f64() * 1e3,
            walks: walked.attempts,
            ..LazyReport::default()
        };
        let (computed, ms, growths) = self.synthesize_levels(&walked.sets)?;
        report.table_growths = growths;
        report.needed = walked.sets.iter().map(|s| s.len as u64).collect();
        report.upsampled = walked.sets.iter().map(|s| s.fresh as u64).collect();
        report.computed = computed;
        report.gpu_ms = ms;
        self.walk.give_back(walked.sets);
        Ok(report)
    }

    /// The dependency walk on the GPU (`walk.rs`): per level, coarsest first, the sorted
    /// stage-tagged keys.
    fn walk(&mut self, request: WalkRequest<'_>) -> SynthResult<WalkSets> {
        let schedules: Vec<LevelSchedule> = self.levels.iter().map(|l| l.schedule).collect();
        let info = self.gpu.info();
        let (max_alloc, heap) = (
            info.max_memory_allocation_size.min(info.max_buffer_size),
            info.heap_size,
        );
        let state = self.bytes();
        let check = move |what: &str, bytes: u64, total: u64| {
            check_fits(what, bytes, state + total, max_alloc, heap)
        };
        self.walk
            .walk(self.records.address(), &schedules, request, &check)
    }

    /// Synthesizes the finest-level voxels `requested` (positions in `[0, R)³`) and returns
    /// their final triples in the same order.
    ///
    /// # Errors
    /// A position outside the texture, state that would exceed the device's limits, or a GPU
    /// failure.
    pub fn request(&mut self, requested: &[[i32; 3]]) -> SynthResult<(Vec<[u32; 3]>, LazyReport)> {
        let start = std::time::Instant::now();
        self.check_requested(requested)?;
        let keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
        let n = keys.len();
        if n == 0 {
            let mut report = self.run_chunks(Requested::Host(&keys), &mut |_, _, _| Ok(()))?;
            report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
            return Ok((Vec::new(), report));
        }
        let keys_buf = GpuBuffer::from_slice(&self.gpu, "lazy requested keys", &keys)?;
        let out = GpuBuffer::<[u32; 3]>::new(&self.gpu, "lazy requested triples", n)?;
        let errors = GpuBuffer::<u32>::new(&self.gpu, "lazy gather errors", 1)?;
        let mut report = self.run_chunks(Requested::Host(&keys), &mut |me, first, len| {
            let push = GatherPush {
                levels: me.records.address(),
                keys: keys_buf.address_at(first)?,
                triples: out.address_at(first)?,
                errors: errors.address(),
                n: len as u32,
                level: (me.levels.len() - 1) as u32,
            };
            me.gpu.submit(|rec| {
                if first == 0 {
                    rec.fill(&errors, 0);
                }
                rec.dispatch(&me.gather, me.gather.groups_for(len as u64), &[], &push)
            })?;
            Ok(())
        })?;
        check_errors(&errors, "requested voxels missing or not final")?;
        let triples = out.read()?;
        report.wall_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok((triples, report))
    }

    /// Synthesizes every level's dependency set in two submissions, whatever the number of
    /// levels: first every level's lookups and the inserts of its new voxels (room made
    /// beforehand from the walk's count of them), then every level's upsampling and
    /// correction, coarsest first. Returns per level the versions computed, the device time of
    /// the second submission in milliseconds, and the hash tables made, grown or refilled
    /// (each waits on the host a few times; the growth is geometric).
    fn synthesize_levels(&mut self, sets: &[LevelSet]) -> SynthResult<(Vec<u64>, f64, u32)> {
        let gpu = self.gpu.clone();
        // Room for every level's new voxels: versions and counts (copied at the start of the
        // first submission) and table cells.
        let mut moved = Vec::new();
        let mut growths = 0;
        for (l, set) in sets.iter().enumerate() {
            if set.len == 0 || set.fresh == 0 {
                continue;
            }
            moved.extend(self.reserve_later(l, self.levels[l].len as usize + set.fresh)?);
            let state = &mut self.levels[l];
            let total = u64::from(state.len) + set.fresh as u64;
            match &mut state.table {
                Some(t) => {
                    if t.reserve(total).map_err(|e| hash_error(l, e))? {
                        growths += 1;
                    }
                }
                None => {
                    let config = RobinHoodConfig {
                        validate: true,
                        ..RobinHoodConfig::default()
                    };
                    let t = RobinHoodTable::with_room(&self.hash, state.universe, total, config)
                        .map_err(|e| hash_error(l, e))?;
                    state.table = Some(t);
                    growths += 1;
                }
            }
        }
        self.write_records()?;
        let mut work: Vec<LevelWork> = Vec::new();
        for (l, set) in sets.iter().enumerate() {
            if set.len == 0 {
                continue;
            }
            let n = set.len;
            let fresh = set.fresh;
            let stages = self.levels[l].schedule.final_stage();
            work.push(LevelWork {
                l,
                n,
                fresh,
                base: self.levels[l].len,
                slots: GpuBuffer::new(&gpu, format!("lazy slots level {l}"), n)?,
                flags: GpuBuffer::new(&gpu, format!("lazy new flags level {l}"), n)?,
                totals: GpuBuffer::new(&gpu, format!("lazy new and work level {l}"), 2)?,
                order_keys: GpuBuffer::new(&gpu, format!("lazy order keys level {l}"), n)?,
                order: GpuBuffer::new(&gpu, format!("lazy order level {l}"), n)?,
                new_keys: GpuBuffer::new(&gpu, "lazy new keys", fresh.max(1))?,
                new_payloads: GpuBuffer::new(&gpu, "lazy new slots", fresh.max(1))?,
                append: match (&self.levels[l].table, fresh) {
                    (Some(t), 1..) => Some(t.append_scratch()?),
                    _ => None,
                },
                errors: GpuBuffer::new(&gpu, "lazy synthesis errors", 1)?,
                ranges: GpuBuffer::new(
                    &gpu,
                    format!("lazy stage ranges level {l}"),
                    (stages * LAZY_RANGE_WORDS) as usize,
                )?,
            });
        }
        // Every level's lookups, new slots and inserts.
        gpu.submit(|rec| {
            for m in &moved {
                self.record_move(rec, m)?;
            }
            for w in &work {
                rec.fill(&w.totals, 0);
                rec.fill(&w.errors, 0);
            }
            for w in &work {
                let l = w.l;
                let push = PreparePush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    flags: w.flags.address(),
                    work: w.totals.address_at(1)?,
                    order_keys: w.order_keys.address(),
                    order: w.order.address(),
                    n: w.n as u32,
                    level: l as u32,
                };
                let k = &self.prepare;
                rec.dispatch(k, k.groups_for(w.n as u64), &[], &push)?;
                self.scan
                    .record(rec, &w.flags, &w.flags, w.n, Some(&w.totals))?;
                let (Some(scratch), Some(table)) = (&w.append, &self.levels[l].table) else {
                    continue;
                };
                let push = AssignPush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    offsets: w.flags.address(),
                    new_keys: w.new_keys.address(),
                    new_payloads: w.new_payloads.address(),
                    n: w.n as u32,
                    level: l as u32,
                    base: w.base,
                };
                rec.dispatch(&self.assign, self.assign.groups_for(w.n as u64), &[], &push)?;
                table.record_append(rec, scratch, &w.new_keys, &w.new_payloads, w.fresh)?;
            }
            Ok(())
        })?;
        let mut computed = vec![0u64; sets.len()];
        for w in &mut work {
            let l = w.l;
            let totals = w.totals.read()?;
            if totals[0] as usize != w.fresh {
                return Err(SynthError::Parameter {
                    name: "lazy walk",
                    value: format!("{} new voxels at level {l}", w.fresh),
                    limit: format!("the lookups found {} (a device fault?)", totals[0]),
                });
            }
            computed[l] = u64::from(totals[1]);
            if let Some(scratch) = w.append.take() {
                let table = self.levels[l].table.as_mut().expect("made above");
                let inserted = table
                    .finish_append(scratch, w.fresh)
                    .map_err(|e| hash_error(l, e))?;
                if !inserted {
                    // An age overflowed: the table is as it was; the host insert grows it.
                    table
                        .insert(&w.new_keys, &w.new_payloads, w.fresh)
                        .map_err(|e| hash_error(l, e))?;
                    growths += 1;
                }
            }
            self.levels[l].len += w.fresh as u32;
        }
        self.write_records()?;
        // Every level's upsampling and correction.
        let side = self.synth.side();
        let grouped = self.visit == VisitOrder::Grouped;
        let ((), stamps) = gpu.submit_timed(|rec| {
            rec.timestamp()?;
            for w in &work {
                let l = w.l;
                if computed[l] == 0 {
                    continue;
                }
                let n = w.n;
                let spacing = self.synth.spacing(l);
                let table = self.synth.level_table(l);
                let schedule = self.levels[l].schedule;
                // The correction's visiting order (lazy_prepare.comp) and each stage's
                // stretch of it: a stage visits only the voxels it may correct, side by side
                // in whole SIMD groups. Unsorted, `order` is the identity and every stretch
                // all of it.
                if grouped {
                    self.sort
                        .record_u32_pairs(rec, &w.order_keys, &w.order, n, LAZY_ORDER_BITS)?;
                }
                self.stage_ranges.record(
                    rec,
                    &w.order_keys,
                    &w.ranges,
                    n,
                    schedule,
                    !grouped,
                    self.correct.workgroup_size(),
                )?;
                let push = LazyUpsamplePush {
                    levels: self.records.address(),
                    keys: sets[l].tagged.address(),
                    slots: w.slots.address(),
                    errors: w.errors.address(),
                    n: n as u32,
                    level: l as u32,
                    side,
                    spacing,
                    seed: self.params.seed,
                    strength: self.params.jitter[l],
                };
                let k = &self.upsample;
                rec.dispatch(k, k.groups_for(n as u64), &[], &push)?;
                for stage in 1..=schedule.final_stage() {
                    let cls = schedule.stage_class(stage);
                    let push = LazyCorrectPush {
                        levels: self.records.address(),
                        table: table.address(),
                        keys: sets[l].tagged.address(),
                        order: w.order.address(),
                        ranges: w.ranges.address(),
                        slots: w.slots.address(),
                        errors: w.errors.address(),
                        level: l as u32,
                        stage,
                        cls,
                        version: schedule.version_at(stage, cls),
                        side,
                        spacing,
                        keep_current: self.params.keep_current as u32,
                        seed: self.params.seed,
                        strength: self.params.jitter[l],
                    };
                    rec.dispatch_indirect(
                        &self.correct,
                        &w.ranges,
                        u64::from((stage - 1) * LAZY_RANGE_WORDS),
                        &[],
                        &push,
                    )?;
                }
            }
            rec.timestamp()
        })?;
        for w in &work {
            check_errors(&w.errors, "dependencies missing during synthesis")?;
        }
        Ok((computed, (stamps[1] - stamps[0]) * 1e-6, growths))
    }

    /// Grows level `l`'s versions and counts to hold `slots` voxels, returning the copy of
    /// what they held for the caller to record before any work reads the level.
    fn reserve_later(&mut self, l: usize, slots: usize) -> SynthResult<Option<MovedLevel>> {
        let state = &self.levels[l];
        let have = state.counts.len();
        if slots <= have {
            return Ok(None);
        }
        let stride = state.stride as usize;
        // Half as much again, so that a level growing over many chunks copies its versions
        // a logarithmic number of times.
        let grown = slots.max(have + have / 2).div_ceil(INITIAL_SLOTS) * INITIAL_SLOTS;
        let words = grown as u64 * 3 * stride as u64;
        if words > u32::MAX as u64 {
            return Err(SynthError::Parameter {
                name: "lazy state",
                value: format!("{grown} voxels at level {l}"),
                limit: format!(
                    "at most {} voxels per level (32-bit word indices)",
                    u32::MAX as u64 / (3 * stride as u64)
                ),
            });
        }
        self.resize_later(l, grown).map(Some)
    }

    /// Moves level `l`'s versions and counts into buffers of `grown` voxels (at least the
    /// voxels it holds), refusing what the device cannot hold, and returns the copy of what
    /// they held for the caller to record before any work reads the level.
    fn resize_later(&mut self, l: usize, grown: usize) -> SynthResult<MovedLevel> {
        let stride = self.levels[l].stride as usize;
        let words = grown as u64 * 3 * stride as u64;
        let info = self.gpu.info();
        let kept = self.levels.iter().map(LevelState::bytes).sum::<u64>();
        let old = self.levels[l].versions.bytes() + self.levels[l].counts.bytes();
        check_fits(
            &format!("the versions of level {l}"),
            words * 4,
            kept - old + words * 4 + grown as u64 * 4,
            info.max_memory_allocation_size.min(info.max_buffer_size),
            info.heap_size,
        )?;
        let state = &mut self.levels[l];
        let versions = GpuBuffer::<u32>::new(
            &self.gpu,
            format!("lazy versions level {l}"),
            words as usize,
        )?;
        let counts = GpuBuffer::<u32>::new(&self.gpu, format!("lazy counts level {l}"), grown)?;
        let used = state.len as usize;
        Ok(MovedLevel {
            l,
            versions: std::mem::replace(&mut state.versions, versions),
            counts: std::mem::replace(&mut state.counts, counts),
            used,
        })
    }

    /// Records the copy of a moved level's versions and counts into its new buffers (the
    /// counts past its voxels zeroed).
    fn record_move(
        &self,
        rec: &mut lazysolid_compute::gpu::Recorder<'_>,
        m: &MovedLevel,
    ) -> lazysolid_compute::gpu::GpuResult<()> {
        let state = &self.levels[m.l];
        let words = m.used * 3 * state.stride as usize;
        rec.fill(&state.counts, 0);
        rec.copy(&m.versions, 0, &state.versions, 0, words)?;
        rec.copy(&m.counts, 0, &state.counts, 0, m.used)
    }
}

/// Share of the device heap the kept state and one step's buffers may take: the rest is left
/// to the radix sort's scratch, the stores and the renderer.
const HEAP_SHARE: f64 = 0.75;

/// Refuses a buffer of `bytes` (`what`) over the device's largest allocation `max_alloc`, or a
/// request whose kept state and buffers (`total` bytes) would pass [`HEAP_SHARE`] of `heap`,
/// naming the limit.
fn check_fits(what: &str, bytes: u64, total: u64, max_alloc: u64, heap: u64) -> SynthResult<()> {
    let mib = |b: u64| format!("{:.1} MiB", b as f64 / (1u64 << 20) as f64);
    if bytes > max_alloc {
        return Err(SynthError::Parameter {
            name: "lazy synthesis request",
            value: format!("{} for {what}", mib(bytes)),
            limit: format!(
                "the device's largest buffer is {} (request fewer voxels at once, or a lower \
                 resolution)",
                mib(max_alloc)
            ),
        });
    }
    let budget = (heap as f64 * HEAP_SHARE) as u64;
    if total > budget {
        return Err(SynthError::Parameter {
            name: "lazy synthesis request",
            value: format!("{} of kept state and buffers at {what}", mib(total)),
            limit: format!(
                "{:.0} % of the device heap, {} (request fewer voxels, or a lower resolution)",
                HEAP_SHARE * 100.0,
                mib(budget)
            ),
        });
    }
    Ok(())
}

fn check_errors(errors: &GpuBuffer<u32>, what: &str) -> SynthResult<()> {
    let e = errors.read()?[0];
    if e != 0 {
        return Err(SynthError::Parameter {
            name: "lazy synthesis",
            value: format!("{e} {what}"),
            limit: "the dependency sets must cover every read".into(),
        });
    }
    Ok(())
}

fn hash_error(level: usize, e: lazysolid_compute::hash::HashError) -> SynthError {
    SynthError::Parameter {
        name: "lazy state table",
        value: format!("level {level}"),
        limit: e.to_string(),
    }
}

/// Every role's packed texels (`role_texel`), role after role, as the colour kernel reads them.
fn role_texels(exemplars: &SolidExemplars, relief: Option<&SolidRelief>) -> Vec<u32> {
    let side = exemplars.side();
    (0..ROLES)
        .flat_map(|r| {
            (0..side * side).map(move |i| role_texel(exemplars, relief, r, i % side, i / side))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::check_fits;

    #[test]
    fn requests_past_the_device_limits_are_refused_with_the_limit() {
        let mib = 1u64 << 20;
        assert!(check_fits("x", 10 * mib, 100 * mib, 128 * mib, 2048 * mib).is_ok());
        let e = check_fits(
            "the versions of level 6",
            200 * mib,
            300 * mib,
            128 * mib,
            2048 * mib,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("200.0 MiB for the versions of level 6") && e.contains("128.0 MiB"),
            "{e}"
        );
        let e = check_fits(
            "the dependency set of level 5",
            10 * mib,
            1600 * mib,
            128 * mib,
            2048 * mib,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("1600.0 MiB") && e.contains("75 % of the device heap, 1536.0 MiB"),
            "{e}"
        );
    }
}
