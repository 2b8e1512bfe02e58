//! The multiscale synthesizer on the GPU (`glsl/synth/multiscale_*.comp`): the analysis of every
//! distinct depth set uploaded once, then per depth one submission of the upsample-and-jitter
//! kernel and `4 × passes` correction subpasses over the state buffer (5 words per pixel:
//! coordinate, meta, transfer). Equal to [`super::synthesize_multiscale_cpu`] exactly.

use super::analysis::MultiscaleAnalysis;
use super::cpu::{
    check_multiscale_window, plan_multiscale, MultiscaleLevel, MultiscaleParams,
    MultiscaleSynthesis, PixelState,
};
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use crate::kernels::synth;
use crate::synth::cpu::CLASSES;
use crate::synth::error::SynthResult;
use crate::synth::gpu::{class_span, LevelTimes};
use crate::synth::neighbourhood::pack_i8_words;
use crate::synth::plan::Region;
use std::sync::Arc;

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsUpsamplePush<'a> {
        parent: DeviceAddress<'a>,
        states: DeviceAddress<'a>,
        exemplars: DeviceAddress<'a>,
        origin: [i32; 2],
        size: [u32; 2],
        parent_origin: [i32; 2],
        parent_size: [u32; 2],
        origin_mod: [u32; 2],
        root: u32,
        depth: u32,
        seed: u32,
        strength: u32,
        has_parent: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsCorrectPush<'a> {
        states: DeviceAddress<'a>,
        exemplars: DeviceAddress<'a>,
        members: DeviceAddress<'a>,
        lookup: DeviceAddress<'a>,
        appearance: DeviceAddress<'a>,
        records: DeviceAddress<'a>,
        candidates: DeviceAddress<'a>,
        matrix: DeviceAddress<'a>,
        origin: [i32; 2],
        size: [u32; 2],
        first: [u32; 2],
        count: [u32; 2],
        k: u32,
        penalty: u32,
    }
}

/// Lookup slots per exemplar (levels `0..=L`, `L ≤ 8`).
const LEVEL_SLOTS: usize = 16;

struct GpuSet {
    members: GpuBuffer<u32>,
    lookup: GpuBuffer<u32>,
    appearance: GpuBuffer<u32>,
    records: GpuBuffer<u32>,
    candidates: GpuBuffer<u32>,
    matrix: GpuBuffer<u32>,
}

/// A graph analysis on the GPU.
pub struct MultiscaleGpu {
    gpu: Gpu,
    upsample: Arc<Kernel>,
    correct: Arc<Kernel>,
    exemplars: GpuBuffer<u32>,
    sets: Vec<GpuSet>,
}

fn state_words(states: &[u32]) -> Vec<PixelState> {
    states
        .chunks_exact(5)
        .map(|w| PixelState {
            coord: w[0],
            meta: w[1],
            transfer: [w[2] as i32, w[3] as i32, w[4] as i32],
        })
        .collect()
}

impl MultiscaleGpu {
    /// Builds the kernels and uploads `analysis`.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn new(gpu: &Gpu, analysis: &MultiscaleAnalysis) -> SynthResult<MultiscaleGpu> {
        let exemplar_words: Vec<u32> = analysis
            .exemplars
            .iter()
            .flat_map(|e| [e.width, e.height, e.finest, 0])
            .collect();
        let mut sets = Vec::new();
        for (s, set) in analysis.sets.iter().enumerate() {
            let mut members = Vec::new();
            let mut lookup = vec![u32::MAX; analysis.exemplars.len() * LEVEL_SLOTS];
            let (mut appearance, mut records, mut candidates) =
                (Vec::new(), Vec::new(), Vec::new());
            for (m, member) in set.members.iter().enumerate() {
                let e = &analysis.exemplars[member.exemplar];
                lookup[member.exemplar * LEVEL_SLOTS + member.level as usize] = m as u32;
                members.extend_from_slice(&[
                    (appearance.len() / 2) as u32,
                    (records.len() / 8) as u32,
                    (candidates.len() / 4) as u32,
                    e.width | (e.height << 16),
                    member.exemplar as u32,
                    member.level,
                    member.spacing,
                    0,
                ]);
                appearance.extend(pack_i8_words(member.appearance.as_flattened()));
                records.extend(pack_i8_words(member.neighbourhoods.as_flattened()));
                for c in &member.candidates {
                    candidates.extend_from_slice(&[
                        c.coord,
                        c.member | ((c.transfer[2] as u32 & 0xffff) << 16),
                        c.transfer[0] as u32,
                        c.transfer[1] as u32,
                    ]);
                }
            }
            let matrix: Vec<u32> = set
                .offset_matrix
                .iter()
                .flat_map(|row| row.map(|v| v as u32))
                .collect();
            let buf = |name: &str, data: &[u32]| {
                GpuBuffer::from_slice(gpu, format!("multiscale {name} set {s}"), data)
            };
            sets.push(GpuSet {
                members: buf("members", &members)?,
                lookup: buf("lookup", &lookup)?,
                appearance: buf("appearance", &appearance)?,
                records: buf("records", &records)?,
                candidates: buf("candidates", &candidates)?,
                matrix: buf("matrix", &matrix)?,
            });
        }
        Ok(MultiscaleGpu {
            gpu: gpu.clone(),
            upsample: gpu.kernel(&synth::MULTISCALE_UPSAMPLE)?,
            correct: gpu.kernel(&synth::MULTISCALE_CORRECT)?,
            exemplars: GpuBuffer::from_slice(gpu, "multiscale exemplars", &exemplar_words)?,
            sets,
        })
    }

    /// Synthesizes `window` of depth `params.depth()`; `keep_levels` reads every depth back,
    /// otherwise only the deepest. Also returns each depth's device time.
    ///
    /// # Errors
    /// A window out of range, or a GPU failure.
    pub fn synthesize(
        &self,
        analysis: &MultiscaleAnalysis,
        params: &MultiscaleParams,
        window: Region,
        keep_levels: bool,
    ) -> SynthResult<(MultiscaleSynthesis, Vec<LevelTimes>)> {
        check_multiscale_window(window)?;
        let regions = plan_multiscale(window, &params.passes);
        let depth = params.depth();
        let root = analysis.topology.root;
        let re = &analysis.exemplars[root];
        let mut levels = Vec::new();
        let mut times = Vec::new();
        let mut parent: Option<(Region, GpuBuffer<u32>)> = None;
        for (t, &region) in regions.iter().enumerate() {
            let set = &self.sets[analysis.superexemplar.set_of(t as u32)];
            let states = GpuBuffer::<u32>::new(
                &self.gpu,
                format!("multiscale states depth {t}"),
                region.pixels() * 5,
            )?;
            let push = MsUpsamplePush {
                parent: parent
                    .as_ref()
                    .map_or(states.address(), |(_, b)| b.address()),
                states: states.address(),
                exemplars: self.exemplars.address(),
                origin: region.origin,
                size: region.size,
                parent_origin: parent.as_ref().map_or([0; 2], |(r, _)| r.origin),
                parent_size: parent.as_ref().map_or([0; 2], |(r, _)| r.size),
                origin_mod: [
                    region.origin[0].rem_euclid(re.width as i32) as u32,
                    region.origin[1].rem_euclid(re.height as i32) as u32,
                ],
                root: root as u32,
                depth: t as u32,
                seed: params.seed,
                strength: params.jitter[t],
                has_parent: parent.is_some() as u32,
            };
            let ((), stamps) = self.gpu.submit_timed(|rec| {
                rec.timestamp()?;
                let k = &self.upsample;
                rec.dispatch(k, k.groups_for(region.pixels() as u64), &[], &push)?;
                rec.timestamp()?;
                for _ in 0..params.passes[t] {
                    for class in CLASSES {
                        let (fx, cx) = class_span(region.origin[0], region.size[0], class[0]);
                        let (fy, cy) = class_span(region.origin[1], region.size[1], class[1]);
                        if cx * cy == 0 {
                            continue;
                        }
                        let push = MsCorrectPush {
                            states: states.address(),
                            exemplars: self.exemplars.address(),
                            members: set.members.address(),
                            lookup: set.lookup.address(),
                            appearance: set.appearance.address(),
                            records: set.records.address(),
                            candidates: set.candidates.address(),
                            matrix: set.matrix.address(),
                            origin: region.origin,
                            size: region.size,
                            first: [fx, fy],
                            count: [cx, cy],
                            k: analysis.k,
                            penalty: params.period_penalty,
                        };
                        let k = &self.correct;
                        rec.dispatch(k, k.groups_for(cx as u64 * cy as u64), &[], &push)?;
                    }
                }
                rec.timestamp()
            })?;
            times.push(LevelTimes {
                level: t as u32,
                pixels: region.pixels() as u64,
                upsample_ms: (stamps[1] - stamps[0]) * 1e-6,
                correct_ms: (stamps[2] - stamps[1]) * 1e-6,
            });
            if keep_levels || t as u32 == depth {
                levels.push(MultiscaleLevel {
                    region,
                    states: state_words(&states.read()?),
                });
            }
            parent = Some((region, states));
        }
        Ok((MultiscaleSynthesis { window, levels }, times))
    }
}
