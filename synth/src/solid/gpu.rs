//! The volume synthesizer on the GPU: analysis and candidates uploaded once, then per level one
//! submission of `upsample_jitter.comp` and `8 × passes` subpasses of `correct.comp`.

use super::analysis::SolidAnalysis;
use super::candidates::SolidCandidates;
use super::cpu::check_solid;
use super::plan::{plan_boxes, plan_levels, VolumeBox};
use super::roles::ROLES;
use super::schedule::{level_schedules, LevelSchedule};
use super::volume::{LevelTriples, SolidSynthesis};
use crate::kernels::synth_solid;
use crate::neighbourhood::pack_i8_words;
use crate::{LevelTimes, SynthParams, SynthResult};
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct UpsamplePush<'a> {
        parent: DeviceAddress<'a>,
        triples: DeviceAddress<'a>,
        origin: [i32; 3],
        size: [u32; 3],
        parent_origin: [i32; 3],
        parent_size: [u32; 3],
        origin_mod: [u32; 3],
        side: u32,
        spacing: u32,
        level: u32,
        seed: u32,
        strength: u32,
        has_parent: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct CorrectPush<'a> {
        triples: DeviceAddress<'a>,
        source: DeviceAddress<'a>,
        table: DeviceAddress<'a>,
        origin: [i32; 3],
        size: [u32; 3],
        first: [u32; 3],
        count: [u32; 3],
        side: u32,
        spacing: u32,
        keep_current: u32,
        step: u32,
    }
}

/// One role of one level on the GPU.
struct GpuRole {
    appearance: GpuBuffer<u32>,
    records: GpuBuffer<u32>,
    candidates: GpuBuffer<[u32; 3]>,
    counts: GpuBuffer<u32>,
    /// Usage penalty per pixel (zeros without a balance).
    penalties: GpuBuffer<u32>,
}

/// One level on the GPU: its spacing, its roles, and the table of the roles' 15 buffer
/// addresses the correction reads (lavapipe's push constants hold only 128 bytes).
struct GpuLevel {
    spacing: u32,
    roles: [GpuRole; ROLES],
    table: GpuBuffer<u64>,
}

/// Analysis and candidates on the GPU, ready to synthesize any number of boxes.
pub struct GpuSolidSynthesizer {
    gpu: Gpu,
    upsample: Arc<Kernel>,
    correct: Arc<Kernel>,
    levels: Vec<GpuLevel>,
    side: u32,
}

impl GpuSolidSynthesizer {
    /// Builds the kernels and uploads `analysis` and `candidates`.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn new(
        gpu: &Gpu,
        analysis: &SolidAnalysis,
        candidates: &SolidCandidates,
    ) -> SynthResult<GpuSolidSynthesizer> {
        let mut levels = Vec::with_capacity(analysis.levels.len());
        for (l, (lv, sets)) in analysis.levels.iter().zip(&candidates.levels).enumerate() {
            let mut roles = Vec::with_capacity(ROLES);
            for (r, set) in sets.iter().enumerate() {
                let name = |what: &str| format!("solid {what} level {l} role {r}");
                roles.push(GpuRole {
                    appearance: GpuBuffer::from_slice(
                        gpu,
                        name("appearance"),
                        &pack_i8_words(lv.roles[r].appearance.as_flattened()),
                    )?,
                    records: GpuBuffer::from_slice(
                        gpu,
                        name("neighbourhoods"),
                        &pack_i8_words(lv.roles[r].neighbourhoods.as_flattened()),
                    )?,
                    candidates: GpuBuffer::from_slice(gpu, name("candidates"), &set.triples)?,
                    counts: GpuBuffer::from_slice(gpu, name("candidate counts"), &set.counts)?,
                    penalties: match candidates.balance.get(l) {
                        Some(b) => GpuBuffer::from_slice(gpu, name("usage penalties"), &b[r])?,
                        None => GpuBuffer::zeroed(
                            gpu,
                            name("usage penalties"),
                            (analysis.side * analysis.side) as usize,
                        )?,
                    },
                });
            }
            let roles: [GpuRole; ROLES] = roles
                .try_into()
                .unwrap_or_else(|_| unreachable!("three roles"));
            let table: Vec<u64> = (0..ROLES)
                .map(|r| roles[r].appearance.address().raw())
                .chain((0..ROLES).map(|r| roles[r].records.address().raw()))
                .chain((0..ROLES).map(|r| roles[r].candidates.address().raw()))
                .chain((0..ROLES).map(|r| roles[r].counts.address().raw()))
                .chain((0..ROLES).map(|r| roles[r].penalties.address().raw()))
                .collect();
            levels.push(GpuLevel {
                spacing: lv.spacing,
                table: GpuBuffer::from_slice(
                    gpu,
                    format!("solid address table level {l}"),
                    &table,
                )?,
                roles,
            });
        }
        Ok(GpuSolidSynthesizer {
            gpu: gpu.clone(),
            upsample: gpu.kernel(&synth_solid::UPSAMPLE_JITTER)?,
            correct: gpu.kernel(&synth_solid::CORRECT)?,
            levels,
            side: analysis.side,
        })
    }

    /// Synthesizes `window` of the finest level; `keep_levels` reads every level back,
    /// otherwise only the finest. Also returns the device time of every level's kernels and
    /// the largest sum of level buffers alive at once (bytes).
    ///
    /// # Errors
    /// A window or parameter set that does not fit, or a GPU failure.
    pub fn synthesize(
        &self,
        analysis: &SolidAnalysis,
        candidates: &SolidCandidates,
        params: &SynthParams,
        window: VolumeBox,
        keep_levels: bool,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<(SolidSynthesis, Vec<LevelTimes>)> {
        check_solid(analysis, candidates, params, window)?;
        let finest = self.levels.len() - 1;
        let plans = plan_levels(window, &level_schedules(params));
        let mut levels = Vec::new();
        let mut times = Vec::with_capacity(plans.len());
        let mut parent: Option<(VolumeBox, GpuBuffer<[u32; 3]>)> = None;
        for (l, plan) in plans.iter().enumerate() {
            let region = plan.region;
            let level = &self.levels[l];
            let spacing = &level.spacing;
            let triples = GpuBuffer::<[u32; 3]>::new(
                &self.gpu,
                format!("solid triples level {l}"),
                region.voxels(),
            )?;
            // A parallel pass reads the state before it from a copy.
            let before = if plan.subpasses.iter().any(|s| s.class.is_none()) {
                Some(GpuBuffer::<[u32; 3]>::new(
                    &self.gpu,
                    format!("solid triples before a parallel pass, level {l}"),
                    region.voxels(),
                )?)
            } else {
                None
            };
            let push = UpsamplePush {
                parent: parent
                    .as_ref()
                    .map_or(triples.address(), |(_, b)| b.address()),
                triples: triples.address(),
                origin: region.origin,
                size: region.size,
                parent_origin: parent.as_ref().map_or([0; 3], |(r, _)| r.origin),
                parent_size: parent.as_ref().map_or([0; 3], |(r, _)| r.size),
                origin_mod: region.origin.map(|o| o.rem_euclid(self.side as i32) as u32),
                side: self.side,
                spacing: *spacing,
                level: l as u32,
                seed: params.seed,
                strength: params.jitter[l],
                has_parent: parent.is_some() as u32,
            };
            let ((), stamps) = self.gpu.submit_timed(|rec| {
                rec.timestamp()?;
                let k = &self.upsample;
                rec.dispatch(k, k.groups_for(region.voxels() as u64), &[], &push)?;
                rec.timestamp()?;
                for subpass in &plan.subpasses {
                    let spans = subpass.span();
                    let n: u64 = spans.iter().map(|s| s.1 as u64).product();
                    let source = match (&before, subpass.class) {
                        (Some(before), None) => {
                            rec.copy(&triples, 0, before, 0, region.voxels())?;
                            before.address()
                        }
                        _ => triples.address(),
                    };
                    let push = CorrectPush {
                        triples: triples.address(),
                        source,
                        table: level.table.address(),
                        origin: region.origin,
                        size: region.size,
                        first: std::array::from_fn(|a| (spans[a].0 - region.origin[a]) as u32),
                        count: spans.map(|s| s.1),
                        side: self.side,
                        spacing: *spacing,
                        keep_current: params.keep_current as u32,
                        step: spans[0].2,
                    };
                    let k = &self.correct;
                    rec.dispatch(k, k.groups_for(n), &[], &push)?;
                }
                rec.timestamp()
            })?;
            times.push(LevelTimes {
                level: l as u32,
                pixels: region.voxels() as u64,
                upsample_ms: (stamps[1] - stamps[0]) * 1e-6,
                correct_ms: (stamps[2] - stamps[1]) * 1e-6,
            });
            if keep_levels || l == finest {
                levels.push(LevelTriples {
                    region,
                    triples: triples.read()?,
                });
            }
            on_level(l as u32);
            parent = Some((region, triples));
        }
        Ok((SolidSynthesis { window, levels }, times))
    }

    /// Side of the exemplars.
    pub(crate) fn side(&self) -> u32 {
        self.side
    }

    /// Spacing of level `l`.
    pub(crate) fn spacing(&self, l: usize) -> u32 {
        self.levels[l].spacing
    }

    /// The table of level `l`'s 12 buffer addresses the correction reads.
    pub(crate) fn level_table(&self, l: usize) -> &GpuBuffer<u64> {
        &self.levels[l].table
    }

    /// Bytes of the two largest consecutive level buffers (a level and its parent are alive
    /// together; a parallel level also holds a copy of its own), plus the uploaded analysis
    /// and candidates: the peak GPU memory of a synthesis of `window` with `schedules`.
    pub fn peak_bytes(&self, window: VolumeBox, schedules: &[LevelSchedule]) -> u64 {
        let boxes = plan_boxes(window, schedules);
        let triple = 12u64;
        let own = |l: usize| boxes[l].voxels() as u64 * (1 + schedules[l].parallel as u64);
        let levels = (1..boxes.len())
            .map(|l| (boxes[l - 1].voxels() as u64 + own(l)) * triple)
            .max()
            .unwrap_or(own(0) * triple);
        let resident: u64 = self
            .levels
            .iter()
            .flat_map(|level| level.roles.iter())
            .map(|r| {
                r.appearance.bytes() + r.records.bytes() + r.candidates.bytes() + r.counts.bytes()
            })
            .sum();
        levels + resident
    }
}
