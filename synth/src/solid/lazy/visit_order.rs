//! The order lazy synthesis's correction visits a level's voxels in, and the stretch of it each
//! stage visits.
//!
//! The dependency walk leaves a level's voxels in their keys' Morton order, in which eight
//! neighbours (one SIMD group on lavapipe, a quarter warp on a GPU) hold one voxel of each
//! 2×2×2 class. An ordered level corrects one class per stage, so a stage dispatched over every
//! voxel ran its groups at an eighth of their width, and lavapipe runs the masked lanes' work
//! too. Instead `lazy_prepare.comp` gives every voxel a key ([`order_key`]: no work last, then
//! the class, then the last stage it is needed at, latest first), the radix sort orders the
//! voxels' indices by it, and `lazy_stage_ranges.comp` finds each stage's stretch of that
//! order by binary search ([`stage_range`], its CPU reference). `lazy_correct.comp` is then
//! dispatched indirectly over the stretch alone. It still checks every voxel it visits, so the
//! versions are those of the keys' order, bit for bit; [`VisitOrder::Keys`] keeps that order for
//! a profile's comparison (`lazysolid bench lazy --profile-correction`).

use super::super::schedule::LevelSchedule;
use crate::kernels::synth_solid;
use crate::shader_constants::LAZY_RANGE_WORDS;
use crate::solid::plan::SUBPASSES_3D;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Kernel, Recorder};
use std::sync::Arc;

/// The order `lazy_correct.comp` visits a level's voxels in. Both give the same versions; the
/// order decides how many lanes of a SIMD group (a warp on a GPU) work together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum VisitOrder {
    /// Sorted on [`order_key`], each stage dispatched over its own stretch.
    #[default]
    Grouped,
    /// The keys' Morton order, every stage dispatched over every voxel: kept so that a profile
    /// measures what the grouping gains (`docs/lazy.md`, "Where the device time goes").
    Keys,
}

/// A voxel's visiting key (`lazy_order_key` in `synth/lazy.glsl`): `idle` for a voxel the
/// level computes nothing for, its class place (0 on a parallel level), the last stage it is
/// needed at (stages past 63 share the last place).
pub fn order_key(idle: bool, class: u32, stage: u32) -> u32 {
    (u32::from(idle) << 9) | (class << 6) | (63 - stage.min(63))
}

/// The stretch `(first, length)` of the sorted visiting keys `sorted` that stage `stage`
/// (1-based) of a level run by `schedule` visits: the voxels with work of the stage's class
/// needed at that stage or later.
pub fn stage_range(sorted: &[u32], schedule: LevelSchedule, stage: u32) -> (u32, u32) {
    let class = if schedule.parallel {
        0
    } else {
        (stage - 1) % SUBPASSES_3D
    };
    let first = sorted.partition_point(|&k| k < order_key(false, class, 63));
    let end = sorted.partition_point(|&k| k < order_key(false, class, stage) + 1);
    (first as u32, (end - first) as u32)
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct StageRangesPush<'a> {
        order_keys: DeviceAddress<'a>,
        ranges: DeviceAddress<'a>,
        n: u32,
        stages: u32,
        parallel: u32,
        whole: u32,
        width: u32,
    }
}

/// `lazy_stage_ranges.comp`: every stage's stretch and its indirect workgroup counts.
pub struct StageRanges {
    kernel: Arc<Kernel>,
}

impl StageRanges {
    /// The kernel, from `gpu`'s cache.
    ///
    /// # Errors
    /// A pipeline failure.
    pub fn new(gpu: &Gpu) -> GpuResult<StageRanges> {
        Ok(StageRanges {
            kernel: gpu.kernel(&synth_solid::LAZY_STAGE_RANGES)?,
        })
    }

    /// Records the stretches of `schedule`'s stages over the sorted `keys[..n]` into `ranges`
    /// ([`LAZY_RANGE_WORDS`] words per stage: workgroup counts x, y, z for a kernel of
    /// `width` invocations per workgroup, the stretch's first place and length), or, with
    /// `whole`, all `n` voxels for every stage.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u32>,
        ranges: &GpuBuffer<u32>,
        n: usize,
        schedule: LevelSchedule,
        whole: bool,
        width: u32,
    ) -> GpuResult<()> {
        let stages = schedule.final_stage();
        let push = StageRangesPush {
            order_keys: keys.address(),
            ranges: ranges.address(),
            n: n as u32,
            stages,
            parallel: u32::from(schedule.parallel),
            whole: u32::from(whole),
            width,
        };
        rec.dispatch(
            &self.kernel,
            self.kernel.groups_for(stages.into()),
            &[],
            &push,
        )
    }

    /// The stretches of `schedule`'s stages over the sorted `keys`, run on the device and read
    /// back: `[x, y, z, first, length]` per stage (a test's view of [`StageRanges::record`]).
    ///
    /// # Errors
    /// A GPU failure.
    pub fn run(
        &self,
        gpu: &Gpu,
        keys: &[u32],
        schedule: LevelSchedule,
        width: u32,
    ) -> GpuResult<Vec<[u32; 5]>> {
        let stages = schedule.final_stage() as usize;
        let keys = GpuBuffer::from_slice(gpu, "stage range keys", keys)?;
        let ranges =
            GpuBuffer::<u32>::zeroed(gpu, "stage ranges", stages * LAZY_RANGE_WORDS as usize)?;
        gpu.submit(|rec| self.record(rec, &keys, &ranges, keys.len(), schedule, false, width))?;
        let words = ranges.read()?;
        Ok(words
            .chunks_exact(LAZY_RANGE_WORDS as usize)
            .map(|w| [w[0], w[1], w[2], w[3], w[4]])
            .collect())
    }
}

const _: () = assert!(LAZY_RANGE_WORDS == 5);
