//! The compressed tree built on the device from the project's primitives, producing the same
//! bytes as the CPU build ([`CompressedTree::build`](super::CompressedTree::build)).
//!
//! - Per level, coarse to fine: the residuals and their maximum (one atomic), then the level's
//!   step and codes.
//! - Finest first: the internal flags.
//! - Per level: the preorder by a radix sort of the preorder keys, and the records by a
//!   compaction of the internal flags in that order.
//! - The packing, fine to coarse, a level at a time: y_max (one atomic); every (candidate
//!   scale, record) pair's padding summed per candidate, and the least-padding scale picked by
//!   a 64-bit atomicMin; the block sizes.
//! - The forest level F from the blocks' sums; level F's records placed by an exclusive scan of
//!   their blocks, each deeper level by its parents, every record writing its bytes.
//!
//! The host reads back small counts only: the records per level, each level's y_max (which
//! sizes the candidate search), and the sums that choose F and size the byte buffer.

use super::device::DeviceTree;
use super::error::CtreeError;
use super::field::{to_fixed, ScalarField};
use super::tree::{forest_bytes, header_bytes, Border, CtreeOptions};
use crate::gpu::{DeviceAddress, DeviceRecords, Gpu, GpuBuffer, GpuError, GpuResult, Kernel};
use crate::kernels::ctree as k;
use crate::prims::{CompactOutput, Compactor, Keep, RadixSort, Scan};
use crate::shader_constants::{
    CTREE_BORDER_ANCHORED, CTREE_BORDER_FREE, CTREE_NO_SUBTREE, CTREE_STATS_WORDS, CTREE_STAT_BEST,
    CTREE_STAT_BLOCKS, CTREE_STAT_MAX_OFFSET, CTREE_STAT_STEP,
};
use glam::UVec3;
use std::sync::Arc;

crate::push_block! {
    /// One level's buffers, as `ctree/build.glsl` reads them from the level table.
    #[derive(Clone, Copy, Default)]
    pub(crate) struct LevelTable<'a> {
        values: DeviceAddress<'a>,
        codes: DeviceAddress<'a>,
        internal: DeviceAddress<'a>,
        blocks: DeviceAddress<'a>,
        addresses: DeviceAddress<'a>,
        records: DeviceAddress<'a>,
        count: DeviceAddress<'a>,
    }
}

crate::push_block! {
    #[derive(Clone, Copy, Default)]
    pub(crate) struct BuildPush<'a> {
        field: DeviceAddress<'a>,
        table: DeviceAddress<'a>,
        stats: DeviceAddress<'a>,
        scratch: DeviceAddress<'a>,
        scratch2: DeviceAddress<'a>,
        bytes: DeviceAddress<'a>,
        size: UVec3,
        dims: u32,
        n: u32,
        level: u32,
        count: u32,
        step: u32,
        first_scale: u32,
        records: u32,
        candidates: u32,
        forest: u32,
        border: u32,
    }
}

/// What a device build did, for reports and benchmarks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DeviceBuildReport {
    /// Records of each level 0..L.
    pub records: Vec<u32>,
    /// Candidate scales the search tried per level.
    pub candidates: Vec<u64>,
    /// Padding per level at its chosen scale.
    pub padding: Vec<u64>,
    /// Submissions to the device.
    pub submissions: u32,
}

struct Level {
    values: GpuBuffer<i32>,
    codes: GpuBuffer<i32>,
    internal: GpuBuffer<u32>,
    blocks: GpuBuffer<u32>,
    addresses: GpuBuffer<u32>,
    records: GpuBuffer<u32>,
    count: GpuBuffer<u32>,
}

struct Kernels {
    residuals: Arc<Kernel>,
    quantize: Arc<Kernel>,
    internal: Arc<Kernel>,
    keys: Arc<Kernel>,
    flags: Arc<Kernel>,
    children: Arc<Kernel>,
    pads: Arc<Kernel>,
    pick: Arc<Kernel>,
    blocks: Arc<Kernel>,
    sizes: Arc<Kernel>,
    place: Arc<Kernel>,
    mip: Arc<Kernel>,
}

/// Builds compressed trees on one device; keeps the primitives' scratch between builds.
pub struct CtreeBuilder {
    gpu: Gpu,
    scan: Scan,
    sort: RadixSort,
    compactor: Compactor,
    kernels: Kernels,
}

impl CtreeBuilder {
    /// A builder for `gpu` (compiles its kernels).
    pub fn new(gpu: &Gpu) -> GpuResult<CtreeBuilder> {
        Ok(CtreeBuilder {
            gpu: gpu.clone(),
            scan: Scan::new(gpu)?,
            sort: RadixSort::new(gpu)?,
            compactor: Compactor::new(gpu)?,
            kernels: Kernels {
                residuals: gpu.kernel(&k::CTREE_RESIDUALS)?,
                quantize: gpu.kernel(&k::CTREE_QUANTIZE)?,
                internal: gpu.kernel(&k::CTREE_INTERNAL)?,
                keys: gpu.kernel(&k::CTREE_KEYS)?,
                flags: gpu.kernel(&k::CTREE_FLAGS)?,
                children: gpu.kernel(&k::CTREE_CHILDREN)?,
                pads: gpu.kernel(&k::CTREE_PADS)?,
                pick: gpu.kernel(&k::CTREE_PICK)?,
                blocks: gpu.kernel(&k::CTREE_BLOCKS)?,
                sizes: gpu.kernel(&k::CTREE_SIZES)?,
                place: gpu.kernel(&k::CTREE_PLACE)?,
                mip: gpu.kernel(&k::CTREE_MIP)?,
            },
        })
    }

    /// Builds the tree of `field` on the device.
    pub fn build(
        &mut self,
        field: &ScalarField,
        options: &CtreeOptions,
    ) -> Result<(DeviceTree, DeviceBuildReport), CtreeError> {
        let step = options.validate(field)?;
        self.build_checked(field, step, options)
            .map_err(|e| CtreeError::Device(e.to_string()))
    }

    fn build_checked(
        &mut self,
        field: &ScalarField,
        step: i32,
        options: &CtreeOptions,
    ) -> GpuResult<(DeviceTree, DeviceBuildReport)> {
        let forest = options.forest;
        let gpu = self.gpu.clone();
        let lat = field.lattice();
        let finest = lat.finest();
        let count = |l: u32| if l == 0 { 1 } else { lat.count(l) };
        let fixed: Vec<i32> = field.values.iter().map(|&v| to_fixed(v)).collect();
        let field_buf = GpuBuffer::from_slice(&gpu, "ctree field", &fixed)?;
        let levels: Vec<Level> = (0..=finest)
            .map(|l| {
                let c = count(l);
                Ok(Level {
                    values: GpuBuffer::zeroed(&gpu, format!("ctree values {l}"), c)?,
                    codes: GpuBuffer::zeroed(&gpu, format!("ctree codes {l}"), c)?,
                    internal: GpuBuffer::zeroed(&gpu, format!("ctree internal {l}"), c)?,
                    blocks: GpuBuffer::zeroed(&gpu, format!("ctree blocks {l}"), c)?,
                    addresses: GpuBuffer::from_slice(
                        &gpu,
                        format!("ctree addresses {l}"),
                        &vec![CTREE_NO_SUBTREE; c],
                    )?,
                    records: GpuBuffer::zeroed(&gpu, format!("ctree records {l}"), c)?,
                    count: GpuBuffer::zeroed(&gpu, format!("ctree record count {l}"), 1)?,
                })
            })
            .collect::<GpuResult<_>>()?;
        let table: Vec<LevelTable> = levels
            .iter()
            .map(|b| LevelTable {
                values: b.values.address(),
                codes: b.codes.address(),
                internal: b.internal.address(),
                blocks: b.blocks.address(),
                addresses: b.addresses.address(),
                records: b.records.address(),
                count: b.count.address(),
            })
            .collect();
        let table = DeviceRecords::new(&gpu, "ctree level table", &table)?;
        let words = CTREE_STATS_WORDS as usize;
        let mut stats_init = vec![0u64; words * (finest as usize + 1)];
        for l in 0..=finest as usize {
            stats_init[words * l + CTREE_STAT_BEST as usize] = u64::MAX;
        }
        let stats = GpuBuffer::from_slice(&gpu, "ctree stats", &stats_init)?;
        let scratch_len = count(finest - 1).max(1);
        let scratch = GpuBuffer::<u32>::zeroed(&gpu, "ctree scratch", scratch_len)?;
        let scratch2 = GpuBuffer::<u32>::zeroed(&gpu, "ctree scratch 2", scratch_len)?;
        let base = BuildPush {
            field: field_buf.address(),
            table: table.address(),
            stats: stats.address(),
            scratch: scratch.address(),
            scratch2: scratch2.address(),
            size: UVec3::from_array(field.size),
            dims: lat.dims,
            n: lat.n,
            step: step as u32,
            border: match options.border {
                Border::Anchored => CTREE_BORDER_ANCHORED,
                Border::Free => CTREE_BORDER_FREE,
            },
            ..Default::default()
        };
        let kernels = &self.kernels;
        let (sort, compactor, scan) = (&mut self.sort, &mut self.compactor, &mut self.scan);
        let mut report = DeviceBuildReport::default();
        // Quantization, pruning and the preorder record lists.
        gpu.submit(|rec| {
            for l in 0..=finest {
                let push = BuildPush {
                    level: l,
                    count: count(l) as u32,
                    ..base
                };
                let groups = kernels.residuals.groups_for(count(l) as u64);
                rec.dispatch(&kernels.residuals, groups, &[], &push)?;
                rec.dispatch(&kernels.quantize, groups, &[], &push)?;
            }
            for l in (0..finest).rev() {
                let push = BuildPush {
                    level: l,
                    count: count(l) as u32,
                    ..base
                };
                let groups = kernels.internal.groups_for(count(l) as u64);
                rec.dispatch(&kernels.internal, groups, &[], &push)?;
            }
            for (l, level) in levels.iter().enumerate().take(finest as usize) {
                let c = count(l as u32);
                let push = BuildPush {
                    level: l as u32,
                    count: c as u32,
                    ..base
                };
                let groups = kernels.keys.groups_for(c as u64);
                rec.dispatch(&kernels.keys, groups, &[], &push)?;
                let bits = (lat.dims * l as u32).max(1);
                sort.record_u32_pairs(rec, &scratch, &scratch2, c, bits)?;
                rec.dispatch(&kernels.flags, groups, &[], &push)?;
                compactor.record(
                    rec,
                    Some(&scratch2),
                    Keep::Flags(&scratch),
                    c,
                    CompactOutput::Values,
                    &level.records,
                    &level.count,
                )?;
            }
            Ok(())
        })?;
        report.submissions += 1;
        let records: Vec<u32> = levels[..finest as usize]
            .iter()
            .map(|b| b.count.read().map(|v| v[0]))
            .collect::<GpuResult<_>>()?;
        report.records = records.clone();
        // Packing, finest level first.
        let mut totals: Option<GpuBuffer<u64>> = None;
        let stat = |stats: &[u64], l: u32, which: u32| stats[words * l as usize + which as usize];
        for l in (0..finest).rev() {
            let r = records[l as usize];
            let push = BuildPush {
                level: l,
                records: r,
                ..base
            };
            gpu.submit(|rec| {
                let groups = kernels.children.groups_for(r as u64);
                rec.dispatch(&kernels.children, groups, &[], &push)
            })?;
            let max_offset = stat(&stats.read()?, l, CTREE_STAT_MAX_OFFSET);
            let first = max_offset.div_ceil(super::pack::MAX_OFFSET as u64).max(1);
            let last = max_offset.max(1);
            let candidates = last - first + 1;
            report.candidates.push(candidates);
            if totals
                .as_ref()
                .is_none_or(|t| (t.len() as u64) < candidates)
            {
                totals = Some(GpuBuffer::zeroed(
                    &gpu,
                    "ctree candidate totals",
                    candidates as usize,
                )?);
            }
            let totals = totals.as_ref().expect("allocated above");
            let push = BuildPush {
                scratch: totals.address(),
                first_scale: first as u32,
                candidates: candidates as u32,
                ..push
            };
            gpu.submit(|rec| {
                rec.fill(totals, 0);
                let pairs = candidates * r as u64;
                rec.dispatch(&kernels.pads, kernels.pads.groups_for(pairs), &[], &push)?;
                rec.dispatch(
                    &kernels.pick,
                    kernels.pick.groups_for(candidates),
                    &[],
                    &push,
                )?;
                rec.dispatch(
                    &kernels.blocks,
                    kernels.blocks.groups_for(r as u64),
                    &[],
                    &push,
                )
            })?;
            report.submissions += 2;
        }
        report.candidates.reverse();
        let stats_host = stats.read()?;
        let scales: Vec<u32> = (0..finest)
            .map(|l| stat(&stats_host, l, CTREE_STAT_BEST) as u32)
            .collect();
        report.padding = (0..finest)
            .map(|l| stat(&stats_host, l, CTREE_STAT_BEST) >> 32)
            .collect();
        let steps: Vec<i32> = (0..=finest)
            .map(|l| stat(&stats_host, l, CTREE_STAT_STEP) as i32)
            .collect();
        let subtree = |f: u32| stat(&stats_host, f, CTREE_STAT_BLOCKS);
        let total = |f: u32| header_bytes(&lat) + forest_bytes(&lat, f) + subtree(f);
        let f = forest.unwrap_or_else(|| {
            (1..=finest)
                .min_by_key(|&f| (total(f), f))
                .expect("a lattice has a level")
        });
        let byte_len = subtree(f) as usize;
        if byte_len > u32::MAX as usize - 4 {
            return Err(GpuError::InvalidArgument(format!(
                "compressed tree of {byte_len} bytes passes 32-bit addresses"
            )));
        }
        let bytes = GpuBuffer::<u32>::zeroed(&gpu, "ctree records", byte_len.div_ceil(4).max(1))?;
        let pyramid: usize = (1..=f).map(|l| lat.count(l)).sum();
        let mipmap = GpuBuffer::<u32>::zeroed(&gpu, "ctree pyramid", pyramid.div_ceil(2).max(1))?;
        let rf = if f < finest { records[f as usize] } else { 0 };
        gpu.submit(|rec| {
            if f < finest {
                let push = BuildPush {
                    level: f,
                    records: rf,
                    bytes: bytes.address(),
                    ..base
                };
                let groups = kernels.sizes.groups_for(rf as u64);
                rec.dispatch(&kernels.sizes, groups, &[], &push)?;
                scan.record(rec, &scratch, &scratch2, rf as usize, None)?;
                let push = BuildPush {
                    candidates: 1,
                    ..push
                };
                rec.dispatch(&kernels.sizes, groups, &[], &push)?;
                for l in f..finest {
                    let r = records[l as usize];
                    let push = BuildPush {
                        level: l,
                        records: r,
                        ..push
                    };
                    rec.dispatch(
                        &kernels.place,
                        kernels.place.groups_for(r as u64),
                        &[],
                        &push,
                    )?;
                }
            }
            let words = pyramid.div_ceil(2);
            let push = BuildPush {
                bytes: mipmap.address(),
                count: words as u32,
                records: pyramid as u32,
                forest: f,
                ..base
            };
            rec.dispatch(
                &kernels.mip,
                kernels.mip.groups_for(words as u64),
                &[],
                &push,
            )
        })?;
        report.submissions += 1;
        let mut mip_starts = Vec::new();
        let mut start = 0u32;
        for l in 1..=f {
            mip_starts.push(start);
            start += lat.count(l) as u32;
        }
        let mut level_words: Vec<u32> = steps.iter().map(|&s| s as u32).collect();
        level_words.extend(&scales);
        level_words.extend(&mip_starts);
        let mut levels = levels;
        let indirection = levels.swap_remove(f as usize).addresses;
        let tree = DeviceTree::from_parts(
            &gpu,
            bytes,
            byte_len,
            mipmap,
            pyramid,
            indirection,
            GpuBuffer::from_slice(&gpu, "ctree levels", &level_words)?,
            (lat, f, field.size),
        );
        Ok((tree, report))
    }
}
