//! The parallel construction in Vulkan compute, and perfect hashes held on the device.
//!
//! Buckets are counted and grouped with atomics and a scan, then listed by decreasing size
//! class. Each class is placed in a few iterations of two dispatches: every unplaced bucket
//! searches (in the CPU reference's candidate order) for an offset whose slots are all free at
//! the start of the iteration and claims them with a 64-bit atomicMax of (iteration, bucket
//! size, ~bucket); a bucket that won all its slots takes them, the others retry. Within an
//! iteration the largest pending bucket with the smallest id always wins, so every iteration
//! makes progress, and the outcome depends only on sizes and bucket ids — never on thread
//! timing — so a construction is deterministic. The iterations of a class also cover every
//! larger class, so leftovers are retried before smaller buckets fill the table; sweeps over
//! all listed buckets finish whatever remains.
//! Single-key buckets are placed last without any search: the r-th free slot (slot order)
//! goes to the r-th singleton (bucket order), found with a scan and a compaction.

use super::super::error::HashError;
use super::super::keys::{KeyLayout, Universe};
use super::kernels::PerfectKernels;
use super::sizes::PerfectSizes;
use super::table::{PerfectAccess, PerfectAttempt, PerfectConfig, PerfectHash, PerfectReport};
use crate::gpu::{DeviceAddress, GpuBuffer, GpuResult, Recorder};
use crate::kernels::hash;
use crate::prims::{CompactOutput, Keep};
use crate::shader_constants::HASH_NOT_FOUND;
use std::sync::Arc;

/// Size classes counted exactly; larger buckets share the last class.
const CLASSES: u32 = 64;
/// Placement iterations per size class before moving on to the next class.
const ITERATIONS_PER_CLASS: u32 = 3;
/// Sweeps over every listed bucket between two checks of the pending count.
const SWEEPS_PER_CHECK: u32 = 4;
/// Candidate slots one bucket examines per dispatch (llvmpipe caps loops at 65,535 steps).
const BUDGET: u32 = 8192;

crate::push_block! {
    /// The table parameters a kernel passes to `glsl/include/hash/perfect.glsl` (the GLSL
    /// `PerfectHashParams`, 56 bytes, same field order).
    #[derive(Clone, Copy, Debug, Default)]
    pub struct PerfectParams<'a> {
        /// Device address of the packed offset table.
        pub offsets: DeviceAddress<'a>,
        /// Device address of the payload words.
        pub data: DeviceAddress<'a>,
        /// Device address of the tags (0 for constrained access).
        pub tags: DeviceAddress<'a>,
        /// |H|.
        pub h: u32,
        /// |Φ|.
        pub phi: u32,
        /// 2 or 3.
        pub dimensions: u32,
        /// Bits per offset component.
        pub component_bits: u32,
        /// Universe extent along x.
        pub dims_x: u32,
        /// Universe extent along y.
        pub dims_y: u32,
        /// Universe extent along z.
        pub dims_z: u32,
        /// Payload words per slot: 1, or (b+1)³ for blocked tables.
        pub block_words: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct PreparePush<'a> {
        keys: DeviceAddress<'a>,
        h0s: DeviceAddress<'a>,
        buckets: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        anchors: DeviceAddress<'a>,
        status: DeviceAddress<'a>,
        key_count: u64,
        n: u32,
        layout_id: u32,
        dims_x: u32,
        dims_y: u32,
        dims_z: u32,
        dimensions: u32,
        axis_bits: u32,
        h: u32,
        phi: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ScatterPush<'a> {
        buckets: DeviceAddress<'a>,
        h0s: DeviceAddress<'a>,
        starts: DeviceAddress<'a>,
        cursor: DeviceAddress<'a>,
        members: DeviceAddress<'a>,
        member_h0: DeviceAddress<'a>,
        n: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ClassesPush<'a> {
        counts: DeviceAddress<'a>,
        starts: DeviceAddress<'a>,
        members: DeviceAddress<'a>,
        member_h0: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        histogram: DeviceAddress<'a>,
        singles: DeviceAddress<'a>,
        status: DeviceAddress<'a>,
        entries: u32,
        classes: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct OrderPush<'a> {
        counts: DeviceAddress<'a>,
        class_start: DeviceAddress<'a>,
        class_cursor: DeviceAddress<'a>,
        order: DeviceAddress<'a>,
        entries: u32,
        classes: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct ProposePush<'a> {
        order: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        starts: DeviceAddress<'a>,
        anchors: DeviceAddress<'a>,
        h0s: DeviceAddress<'a>,
        member_h0: DeviceAddress<'a>,
        occupied: DeviceAddress<'a>,
        claims: DeviceAddress<'a>,
        state: DeviceAddress<'a>,
        proposal: DeviceAddress<'a>,
        status: DeviceAddress<'a>,
        largest_pending: DeviceAddress<'a>,
        first: u32,
        count: u32,
        iteration: u32,
        h: u32,
        slots: u32,
        dimensions: u32,
        budget: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct VerifyPush<'a> {
        order: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        starts: DeviceAddress<'a>,
        member_h0: DeviceAddress<'a>,
        occupied: DeviceAddress<'a>,
        claims: DeviceAddress<'a>,
        state: DeviceAddress<'a>,
        proposal: DeviceAddress<'a>,
        offsets: DeviceAddress<'a>,
        pending: DeviceAddress<'a>,
        largest_pending: DeviceAddress<'a>,
        first: u32,
        count: u32,
        iteration: u32,
        h: u32,
        dimensions: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct FreeCountPush<'a> {
        occupied: DeviceAddress<'a>,
        free_counts: DeviceAddress<'a>,
        words: u32,
        slots: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct AssignPush<'a> {
        occupied: DeviceAddress<'a>,
        free_ranks: DeviceAddress<'a>,
        singles: DeviceAddress<'a>,
        single_count: DeviceAddress<'a>,
        anchors: DeviceAddress<'a>,
        h0s: DeviceAddress<'a>,
        offsets: DeviceAddress<'a>,
        words: u32,
        slots: u32,
        h: u32,
        dimensions: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct PackPush<'a> {
        offsets: DeviceAddress<'a>,
        words: DeviceAddress<'a>,
        entries: u32,
        h: u32,
        dimensions: u32,
        component_bits: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct FillPush<'a> {
        buckets: DeviceAddress<'a>,
        h0s: DeviceAddress<'a>,
        offsets: DeviceAddress<'a>,
        payloads: DeviceAddress<'a>,
        data: DeviceAddress<'a>,
        tags: DeviceAddress<'a>,
        status: DeviceAddress<'a>,
        n: u32,
        h: u32,
        dimensions: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct QueryPush<'a> {
        table: PerfectParams<'a>,
        keys: DeviceAddress<'a>,
        results: DeviceAddress<'a>,
        key_count: u64,
        n: u32,
        layout_id: u32,
        axis_bits: u32,
        checked: u32,
    }
}

const STATUS_BAD_KEY: usize = 0;
const STATUS_DUPLICATES: usize = 1;
const STATUS_DUPLICATE_KEY: usize = 2;
const STATUS_FAILED: usize = 3;
const STATUS_BAD_PAYLOAD: usize = 4;
const STATUS_FAILED_BUCKET: usize = 5;

pub(crate) fn layout_id(layout: KeyLayout) -> u32 {
    match layout {
        KeyLayout::RowMajor => 0,
        KeyLayout::Morton => 1,
        KeyLayout::BitReversedMorton => 2,
    }
}

/// A perfect hash on the device.
pub struct PerfectHashGpu {
    kernels: Arc<PerfectKernels>,
    universe: Universe,
    sizes: PerfectSizes,
    access: PerfectAccess,
    offsets: GpuBuffer<u32>,
    data: GpuBuffer<u32>,
    tags: Option<GpuBuffer<u32>>,
    block_words: u32,
    /// How the sizes were found.
    pub report: PerfectReport,
}

/// Why one attempt stopped.
enum AttemptError {
    /// Bucket q with this many keys found no offset: grow |Φ|.
    Unplaced(u32, usize),
    /// Anything else: report to the caller.
    Fatal(HashError),
}

impl From<HashError> for AttemptError {
    fn from(e: HashError) -> Self {
        AttemptError::Fatal(e)
    }
}

impl From<crate::gpu::GpuError> for AttemptError {
    fn from(e: crate::gpu::GpuError) -> Self {
        AttemptError::Fatal(e.into())
    }
}

/// Builds perfect hashes on the GPU.
pub struct PerfectBuilder {
    kernels: Arc<PerfectKernels>,
}

impl PerfectBuilder {
    /// A builder using `kernels`.
    pub fn new(kernels: &Arc<PerfectKernels>) -> PerfectBuilder {
        PerfectBuilder {
            kernels: kernels.clone(),
        }
    }

    /// Builds a perfect hash of `keys[..n]` → `payloads[..n]` on the GPU, starting at the same
    /// sizes as [`build_perfect_cpu`](super::build_perfect_cpu) and growing |Φ| the same way
    /// when an attempt fails. There is no silent CPU fallback: build on the CPU and
    /// [`PerfectHashGpu::upload`] for that.
    ///
    /// # Errors
    /// As the CPU construction: keys outside the universe, duplicate keys, a payload equal to
    /// `HASH_NOT_FOUND` with unconstrained access, size limits, `max_attempts` failures, and
    /// device failures.
    pub fn build(
        &self,
        universe: Universe,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        config: PerfectConfig,
    ) -> Result<PerfectHashGpu, HashError> {
        crate::prims::check_len("perfect hash keys", n, keys.len().min(payloads.len()))?;
        let mut sizes = PerfectSizes::initial(n, &universe, config.initial_phi)?;
        let mut report = PerfectReport {
            keys: n,
            attempts: Vec::new(),
        };
        loop {
            match self.attempt(&universe, keys, payloads, n, &sizes, config.access) {
                Ok(mut table) => {
                    report.attempts.push(PerfectAttempt {
                        sizes,
                        bits_per_key: sizes.bits_per_key(n),
                        failure: None,
                    });
                    table.report = report;
                    return Ok(table);
                }
                Err(AttemptError::Fatal(e)) => return Err(e),
                Err(AttemptError::Unplaced(q, size)) => {
                    let reason = super::failure_reason(q, size, &sizes);
                    super::next_attempt(&mut report, &mut sizes, &universe, n, reason, &config)?;
                }
            }
        }
    }

    /// Builds from host slices (uploads them first).
    pub fn build_from_slices(
        &self,
        universe: Universe,
        keys: &[u64],
        payloads: &[u32],
        config: PerfectConfig,
    ) -> Result<PerfectHashGpu, HashError> {
        super::check_inputs(keys.len(), payloads, PerfectAccess::Constrained)?;
        let gpu = &self.kernels.gpu;
        let k = GpuBuffer::from_slice(gpu, "perfect hash keys", &keys_or_one(keys))?;
        let p = GpuBuffer::from_slice(gpu, "perfect hash payloads", &payloads_or_one(payloads))?;
        self.build(universe, &k, &p, keys.len(), config)
    }

    fn attempt(
        &self,
        universe: &Universe,
        keys: &GpuBuffer<u64>,
        payloads: &GpuBuffer<u32>,
        n: usize,
        sizes: &PerfectSizes,
        access: PerfectAccess,
    ) -> Result<PerfectHashGpu, AttemptError> {
        let k = &*self.kernels;
        let gpu = &k.gpu;
        let nb = sizes.entries() as usize;
        let slots = sizes.slots();
        let words = (slots as usize).div_ceil(32);
        let d = sizes.dimensions;
        let buf = |name: &str, len: usize| GpuBuffer::<u32>::new(gpu, name, len.max(1));
        let h0s = buf("perfect h0", n)?;
        let buckets = buf("perfect buckets", n)?;
        let counts = buf("perfect bucket sizes", nb)?;
        let anchors = buf("perfect anchors", nb)?;
        let starts = buf("perfect bucket starts", nb)?;
        let cursor = buf("perfect bucket cursors", nb)?;
        let members = buf("perfect members", n)?;
        let member_h0 = buf("perfect member h0", n)?;
        let histogram = buf("perfect size classes", CLASSES as usize)?;
        let single_flags = buf("perfect singleton flags", nb)?;
        let status =
            GpuBuffer::<u64>::from_slice(gpu, "perfect status", &[0, 0, u64::MAX, 0, 0, u64::MAX])?;
        let mut scan = k.scan.lock().unwrap();
        gpu.submit(|rec| {
            rec.fill(&counts, 0);
            rec.fill(&anchors, u32::MAX);
            rec.fill(&cursor, 0);
            rec.fill(&histogram, 0);
            if n > 0 {
                let push = PreparePush {
                    keys: keys.address(),
                    h0s: h0s.address(),
                    buckets: buckets.address(),
                    counts: counts.address(),
                    anchors: anchors.address(),
                    status: status.address(),
                    key_count: universe.key_count(),
                    n: n as u32,
                    layout_id: layout_id(universe.layout),
                    dims_x: universe.dims[0],
                    dims_y: universe.dims[1],
                    dims_z: universe.dims[2],
                    dimensions: d,
                    axis_bits: universe.axis_bits(),
                    h: sizes.h,
                    phi: sizes.phi,
                };
                let kernel = k.gpu.kernel(&hash::PERFECT_PREPARE)?;
                rec.dispatch(&kernel, kernel.groups_for(n as u64), &[], &push)?;
            }
            scan.record(rec, &counts, &starts, nb, None)?;
            if n > 0 {
                let push = ScatterPush {
                    buckets: buckets.address(),
                    h0s: h0s.address(),
                    starts: starts.address(),
                    cursor: cursor.address(),
                    members: members.address(),
                    member_h0: member_h0.address(),
                    n: n as u32,
                };
                let kernel = k.gpu.kernel(&hash::PERFECT_SCATTER)?;
                rec.dispatch(&kernel, kernel.groups_for(n as u64), &[], &push)?;
            }
            let push = ClassesPush {
                counts: counts.address(),
                starts: starts.address(),
                members: members.address(),
                member_h0: member_h0.address(),
                keys: keys.address(),
                histogram: histogram.address(),
                singles: single_flags.address(),
                status: status.address(),
                entries: nb as u32,
                classes: CLASSES,
            };
            let kernel = k.gpu.kernel(&hash::PERFECT_CLASSES)?;
            rec.dispatch(&kernel, kernel.groups_for(nb as u64), &[], &push)
        })?;
        drop(scan);
        let s = status.read()?;
        if s[STATUS_BAD_KEY] > 0 {
            return Err(HashError::KeyOutsideUniverse {
                key: s[STATUS_BAD_KEY] - 1,
                universe: universe.key_count(),
                description: universe.describe(),
            }
            .into());
        }
        if s[STATUS_DUPLICATES] > 0 {
            return Err(HashError::DuplicateKey {
                key: s[STATUS_DUPLICATE_KEY],
                count: s[STATUS_DUPLICATES],
            }
            .into());
        }
        // Class starts, largest class first.
        let hist = histogram.read()?;
        let mut class_start = vec![0u32; CLASSES as usize];
        let mut multi = 0u32;
        for c in (2..CLASSES as usize).rev() {
            class_start[c] = multi;
            multi += hist[c];
        }
        let class_start_buf = GpuBuffer::from_slice(gpu, "perfect class starts", &class_start)?;
        let class_cursor = buf("perfect class cursors", CLASSES as usize)?;
        let order = buf("perfect bucket order", multi as usize)?;
        let occupied = buf("perfect occupancy", words)?;
        let claims = GpuBuffer::<u64>::new(gpu, "perfect claims", slots as usize)?;
        let state = buf("perfect bucket states", nb)?;
        let proposal = buf("perfect proposals", 2 * nb)?;
        let offsets = buf("perfect offsets", nb)?;
        let largest = [
            buf("perfect largest pending A", 1)?,
            buf("perfect largest pending B", 1)?,
        ];
        let addresses = Addresses {
            largest: [&largest[0], &largest[1]],
            order: order.address(),
            counts: counts.address(),
            starts: starts.address(),
            anchors: anchors.address(),
            h0s: h0s.address(),
            member_h0: member_h0.address(),
            occupied: occupied.address(),
            claims: claims.address(),
            state: state.address(),
            proposal: proposal.address(),
            status: status.address(),
            offsets: offsets.address(),
        };
        let mut iteration = 0u32;
        let classes: Vec<(u32, u32)> = (2..CLASSES as usize)
            .rev()
            .filter(|&c| hist[c] > 0)
            .map(|c| (class_start[c], hist[c]))
            .collect();
        let mut first_pass = true;
        loop {
            let pending = buf("perfect pending", SWEEPS_PER_CHECK as usize + 1)?;
            gpu.submit(|rec| {
                if first_pass {
                    rec.fill(&class_cursor, 0);
                    rec.fill(&occupied, 0);
                    rec.fill(&claims, 0);
                    rec.fill(&state, 0);
                    rec.fill(&proposal, 0);
                    rec.fill(&offsets, 0);
                    rec.fill(&largest[0], 0);
                    rec.fill(&largest[1], 0);
                    let push = OrderPush {
                        counts: counts.address(),
                        class_start: class_start_buf.address(),
                        class_cursor: class_cursor.address(),
                        order: order.address(),
                        entries: nb as u32,
                        classes: CLASSES,
                    };
                    let kernel = k.gpu.kernel(&hash::PERFECT_ORDER)?;
                    rec.dispatch(&kernel, kernel.groups_for(nb as u64), &[], &push)?;
                }
                rec.fill(&pending, 0);
                if first_pass {
                    // Each class with every larger one, so leftovers of larger classes are
                    // retried before smaller buckets fill the table.
                    for &(first, count) in &classes {
                        for _ in 0..ITERATIONS_PER_CLASS {
                            iteration += 1;
                            let target = pending.address_at(SWEEPS_PER_CHECK as usize)?;
                            self.record_round(
                                rec,
                                &addresses,
                                sizes,
                                0,
                                first + count,
                                iteration,
                                target,
                            )?;
                        }
                    }
                }
                for sweep in 0..SWEEPS_PER_CHECK {
                    iteration += 1;
                    let target = pending.address_at(sweep as usize)?;
                    self.record_round(rec, &addresses, sizes, 0, multi, iteration, target)?;
                }
                Ok(())
            })?;
            first_pass = false;
            let s = status.read()?;
            if s[STATUS_FAILED] > 0 {
                let q = s[STATUS_FAILED_BUCKET] as u32;
                let size = counts.read_range(q as usize, 1)?[0] as usize;
                return Err(AttemptError::Unplaced(q, size));
            }
            if pending.read_range(SWEEPS_PER_CHECK as usize - 1, 1)?[0] == 0 {
                break;
            }
        }
        // Singletons, then the packed offsets and the payloads.
        let singles = buf("perfect singletons", nb)?;
        let single_count = buf("perfect singleton count", 1)?;
        let free_ranks = buf("perfect free-slot ranks", words)?;
        let table_words = buf("perfect offset table", sizes.offset_words())?;
        let data = buf("perfect payloads", slots as usize)?;
        let tags = match access {
            PerfectAccess::Unconstrained => Some(buf("perfect tags", slots as usize)?),
            PerfectAccess::Constrained => None,
        };
        let free_count = k.gpu.kernel(&hash::PERFECT_FREE_COUNT)?;
        let mut scan = k.scan.lock().unwrap();
        let mut compact = k.compact.lock().unwrap();
        gpu.submit(|rec| {
            compact.record(
                rec,
                None,
                Keep::Flags(&single_flags),
                nb,
                CompactOutput::Indices,
                &singles,
                &single_count,
            )?;
            let push = FreeCountPush {
                occupied: occupied.address(),
                free_counts: free_ranks.address(),
                words: words as u32,
                slots,
            };
            rec.dispatch(&free_count, free_count.groups_for(words as u64), &[], &push)?;
            scan.record(rec, &free_ranks, &free_ranks, words, None)?;
            let push = AssignPush {
                occupied: occupied.address(),
                free_ranks: free_ranks.address(),
                singles: singles.address(),
                single_count: single_count.address(),
                anchors: anchors.address(),
                h0s: h0s.address(),
                offsets: offsets.address(),
                words: words as u32,
                slots,
                h: sizes.h,
                dimensions: d,
            };
            let kernel = k.gpu.kernel(&hash::PERFECT_ASSIGN)?;
            rec.dispatch(&kernel, kernel.groups_for(words as u64), &[], &push)?;
            rec.fill(&table_words, 0);
            rec.fill(&data, 0);
            if let Some(t) = &tags {
                rec.fill(t, 0);
            }
            let push = PackPush {
                offsets: offsets.address(),
                words: table_words.address(),
                entries: nb as u32,
                h: sizes.h,
                dimensions: d,
                component_bits: sizes.component_bits,
            };
            let kernel = k.gpu.kernel(&hash::PERFECT_PACK)?;
            rec.dispatch(&kernel, kernel.groups_for(nb as u64), &[], &push)?;
            if n > 0 {
                let push = FillPush {
                    buckets: buckets.address(),
                    h0s: h0s.address(),
                    offsets: offsets.address(),
                    payloads: payloads.address(),
                    data: data.address(),
                    tags: tags
                        .as_ref()
                        .map_or(DeviceAddress::NULL, GpuBuffer::address),
                    status: status.address(),
                    n: n as u32,
                    h: sizes.h,
                    dimensions: d,
                };
                let kernel = k.gpu.kernel(&hash::PERFECT_FILL)?;
                rec.dispatch(&kernel, kernel.groups_for(n as u64), &[], &push)?;
            }
            Ok(())
        })?;
        drop((scan, compact));
        if access == PerfectAccess::Unconstrained
            && status.read_range(STATUS_BAD_PAYLOAD, 1)?[0] > 0
        {
            return Err(super::not_found_payload(HASH_NOT_FOUND).into());
        }
        Ok(PerfectHashGpu {
            kernels: self.kernels.clone(),
            universe: *universe,
            sizes: *sizes,
            access,
            offsets: table_words,
            data,
            tags,
            block_words: 1,
            report: PerfectReport::default(),
        })
    }

    /// One placement iteration (propose, then verify) over `order[first..first + count]`.
    #[allow(clippy::too_many_arguments)]
    fn record_round(
        &self,
        rec: &mut Recorder<'_>,
        a: &Addresses<'_>,
        sizes: &PerfectSizes,
        first: u32,
        count: u32,
        iteration: u32,
        pending: DeviceAddress<'_>,
    ) -> GpuResult<()> {
        if count == 0 {
            return Ok(());
        }
        let k = &*self.kernels;
        let push = ProposePush {
            order: a.order,
            counts: a.counts,
            starts: a.starts,
            anchors: a.anchors,
            h0s: a.h0s,
            member_h0: a.member_h0,
            occupied: a.occupied,
            claims: a.claims,
            state: a.state,
            proposal: a.proposal,
            status: a.status,
            largest_pending: a.largest[(iteration as usize + 1) % 2].address(),
            first,
            count,
            iteration,
            h: sizes.h,
            slots: sizes.slots(),
            dimensions: sizes.dimensions,
            budget: BUDGET,
        };
        let kernel = k.gpu.kernel(&hash::PERFECT_PROPOSE)?;
        rec.dispatch(&kernel, kernel.groups_for(count as u64), &[], &push)?;
        let largest = &a.largest[iteration as usize % 2];
        rec.fill(largest, 0);
        let push = VerifyPush {
            order: a.order,
            counts: a.counts,
            starts: a.starts,
            member_h0: a.member_h0,
            occupied: a.occupied,
            claims: a.claims,
            state: a.state,
            proposal: a.proposal,
            offsets: a.offsets,
            pending,
            largest_pending: largest.address(),
            first,
            count,
            iteration,
            h: sizes.h,
            dimensions: sizes.dimensions,
        };
        let kernel = k.gpu.kernel(&hash::PERFECT_VERIFY)?;
        rec.dispatch(&kernel, kernel.groups_for(count as u64), &[], &push)
    }
}

/// Device addresses shared by the placement dispatches.
struct Addresses<'a> {
    /// The largest pending size class left by the last iteration (alternating words).
    largest: [&'a GpuBuffer<u32>; 2],
    order: DeviceAddress<'a>,
    counts: DeviceAddress<'a>,
    starts: DeviceAddress<'a>,
    anchors: DeviceAddress<'a>,
    h0s: DeviceAddress<'a>,
    member_h0: DeviceAddress<'a>,
    occupied: DeviceAddress<'a>,
    claims: DeviceAddress<'a>,
    state: DeviceAddress<'a>,
    proposal: DeviceAddress<'a>,
    status: DeviceAddress<'a>,
    offsets: DeviceAddress<'a>,
}

fn keys_or_one(keys: &[u64]) -> Vec<u64> {
    if keys.is_empty() {
        vec![0]
    } else {
        keys.to_vec()
    }
}

fn payloads_or_one(payloads: &[u32]) -> Vec<u32> {
    if payloads.is_empty() {
        vec![0]
    } else {
        payloads.to_vec()
    }
}

impl PerfectHashGpu {
    /// Uploads a table built on the host (the explicit CPU path).
    pub fn upload(kernels: &Arc<PerfectKernels>, table: &PerfectHash) -> Result<Self, HashError> {
        Self::upload_words(kernels, table, 1)
    }

    pub(crate) fn upload_words(
        kernels: &Arc<PerfectKernels>,
        table: &PerfectHash,
        block_words: u32,
    ) -> Result<Self, HashError> {
        let gpu = &kernels.gpu;
        Ok(PerfectHashGpu {
            kernels: kernels.clone(),
            universe: table.universe,
            sizes: table.sizes,
            access: table.access,
            offsets: GpuBuffer::from_slice(gpu, "perfect offset table", &table.offsets)?,
            data: GpuBuffer::from_slice(gpu, "perfect payloads", &table.data)?,
            tags: match &table.tags {
                Some(t) => Some(GpuBuffer::from_slice(gpu, "perfect tags", t)?),
                None => None,
            },
            block_words,
            report: table.report.clone(),
        })
    }

    /// The parameters for `glsl/include/hash/perfect.glsl`.
    pub fn params(&self) -> PerfectParams<'_> {
        PerfectParams {
            offsets: self.offsets.address(),
            data: self.data.address(),
            tags: self
                .tags
                .as_ref()
                .map_or(DeviceAddress::NULL, GpuBuffer::address),
            h: self.sizes.h,
            phi: self.sizes.phi,
            dimensions: self.sizes.dimensions,
            component_bits: self.sizes.component_bits,
            dims_x: self.universe.dims[0],
            dims_y: self.universe.dims[1],
            dims_z: self.universe.dims[2],
            block_words: self.block_words,
        }
    }

    /// Reads the table back to the host.
    pub fn to_host(&self) -> Result<PerfectHash, HashError> {
        Ok(PerfectHash {
            universe: self.universe,
            sizes: self.sizes,
            access: self.access,
            offsets: self.offsets.read()?,
            data: self.data.read()?,
            tags: match &self.tags {
                Some(t) => Some(t.read()?),
                None => None,
            },
            report: self.report.clone(),
        })
    }

    /// Records `results[i]` = the payload of `keys[i]`; with unconstrained access
    /// `HASH_NOT_FOUND` for keys that are not stored.
    pub fn record_query(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        results: &GpuBuffer<u32>,
        n: usize,
    ) -> GpuResult<()> {
        crate::prims::check_len("perfect hash queries", n, keys.len().min(results.len()))?;
        if n == 0 {
            return Ok(());
        }
        let push = QueryPush {
            table: self.params(),
            keys: keys.address(),
            results: results.address(),
            key_count: self.universe.key_count(),
            n: n as u32,
            layout_id: layout_id(self.universe.layout),
            axis_bits: self.universe.axis_bits(),
            checked: (self.access == PerfectAccess::Unconstrained) as u32,
        };
        let q = self.kernels.gpu.kernel(&hash::PERFECT_QUERY)?;
        rec.dispatch(&q, q.groups_for(n as u64), &[], &push)
    }

    /// Queries `keys` and reads the results back.
    pub fn query(&self, keys: &[u64]) -> GpuResult<Vec<u32>> {
        let gpu = &self.kernels.gpu;
        let k = GpuBuffer::from_slice(gpu, "perfect queries", &keys_or_one(keys))?;
        let r = GpuBuffer::<u32>::new(gpu, "perfect query results", keys.len().max(1))?;
        gpu.submit(|rec| self.record_query(rec, &k, &r, keys.len()))?;
        Ok(r.read()?[..keys.len()].to_vec())
    }

    /// Exact GPU bytes of Φ, H and the tags.
    pub fn bytes(&self) -> u64 {
        self.offsets.bytes() + self.data.bytes() + self.tags.as_ref().map_or(0, |t| t.bytes())
    }

    /// The sizes.
    pub fn sizes(&self) -> &PerfectSizes {
        &self.sizes
    }

    /// The access mode.
    pub fn access(&self) -> PerfectAccess {
        self.access
    }

    /// The universe.
    pub fn universe(&self) -> &Universe {
        &self.universe
    }

    /// The kernels the table was built or uploaded with.
    pub fn kernels(&self) -> &Arc<PerfectKernels> {
        &self.kernels
    }
}
