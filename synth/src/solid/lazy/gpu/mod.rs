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
//! applied after a request's last chunk (a request runs in chunks of [`LAZY_CHUNK_VOXELS`]
//! requested voxels); [`GpuLazySolid::bytes`] reports what is kept.
//!
//! Here: the state, its levels and the kernels' push blocks; `request.rs` runs a request in
//! chunks, `levels.rs` synthesizes one chunk's levels, `memory.rs` applies the policy and
//! grows the buffers within the device's limits, `report.rs` holds the options and reports.

use super::correct_parts::CorrectParts;
use super::deps::{Dependencies, LevelDeps};
use super::keys::{check_within, lazy_key, untag};
use super::policy::{LevelKeep, MemoryPolicy, LAZY_CHUNK_VOXELS};
use super::visit_order::{StageRanges, VisitOrder};
use super::walk::{texture_key_bits, DeviceWalk, LevelSet, WalkRequest, WalkSets};
use crate::kernels::synth_solid;
use crate::shader_constants::{LAZY_ORDER_BITS, LAZY_RANGE_WORDS};
use crate::solid::analysis::SolidAnalysis;
use crate::solid::candidates::SolidCandidates;
use crate::solid::cpu::check_levels;
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

mod levels;
mod memory;
mod report;
mod request;

pub use report::LazyReport;

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
