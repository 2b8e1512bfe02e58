//! The multiscale synthesizer on the GPU (`glsl/synth/multiscale_*.comp`): every distinct depth
//! set uploaded once in its packed layout ([`DepthAtlas`]), then per depth one submission: the
//! upsample-and-jitter kernel over the state buffer (5 words per pixel: coordinate, meta,
//! transfer), the states turned into working states (texel index in the packed layout and
//! transfer), `4 × passes` correction subpasses over those, and the corrected ones turned back.
//! Equal to [`super::synthesize_multiscale_cpu`] exactly.

use super::analysis::MultiscaleAnalysis;
use super::atlas::DepthAtlas;
use super::cpu::{
    check_multiscale_window, plan_multiscale, MultiscaleLevel, MultiscaleParams,
    MultiscaleSynthesis, PixelState,
};
use crate::cpu::CLASSES;
use crate::error::SynthResult;
use crate::gpu::{class_span, LevelTimes};
use crate::kernels::synth;
use crate::plan::Region;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;

lazysolid_compute::push_block! {
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

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsEnterPush<'a> {
        states: DeviceAddress<'a>,
        texel: DeviceAddress<'a>,
        transfer: DeviceAddress<'a>,
        exemplars: DeviceAddress<'a>,
        lookup: DeviceAddress<'a>,
        control: DeviceAddress<'a>,
        pixels: u32,
        zero_texel: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsCorrectPush<'a> {
        texel: DeviceAddress<'a>,
        transfer: DeviceAddress<'a>,
        texels: DeviceAddress<'a>,
        continued: DeviceAddress<'a>,
        appearance: DeviceAddress<'a>,
        records: DeviceAddress<'a>,
        cand_texel: DeviceAddress<'a>,
        cand_extra: DeviceAddress<'a>,
        cand_period: DeviceAddress<'a>,
        exemplars: DeviceAddress<'a>,
        matrix: DeviceAddress<'a>,
        control: DeviceAddress<'a>,
        size: [u32; 2],
        first: [u32; 2],
        count: [u32; 2],
        k: u32,
        penalty: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsExitPush<'a> {
        texel: DeviceAddress<'a>,
        transfer: DeviceAddress<'a>,
        states: DeviceAddress<'a>,
        texels: DeviceAddress<'a>,
        pixels: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct MsSelectPush<'a> {
        control: DeviceAddress<'a>,
        groups: [u32; 3],
    }
}

/// Control words per depth (see glsl/include/synth/multiscale.glsl).
const CONTROL_WORDS: usize = crate::shader_constants::MULTISCALE_CONTROL_WORDS as usize;

/// Which correction kernel a depth runs: a CPU driver executes every branch of a kernel for
/// every lane, so work a depth cannot need is compiled out rather than skipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct CorrectionVariant {
    /// Transfers read, moved and composed (else all are zero).
    pub transfers: bool,
    /// The period test available: the device then runs it from the first subpass where some
    /// pixel sits at a level offering candidates it can penalize (else no candidate of the set
    /// can be penalized, or the penalty is 0).
    pub period: bool,
}

/// A depth set's packed layout on the device ([`DepthAtlas`]).
struct GpuSet {
    lookup: GpuBuffer<u32>,
    texels: GpuBuffer<u32>,
    continued: GpuBuffer<u32>,
    appearance: GpuBuffer<u32>,
    records: GpuBuffer<u32>,
    candidate_texels: GpuBuffer<u32>,
    candidate_extras: GpuBuffer<u32>,
    candidate_periods: GpuBuffer<u32>,
    matrix: GpuBuffer<u32>,
    has_reach: bool,
    has_transfer: bool,
    zero_texel: u32,
}

/// A graph analysis on the GPU.
pub struct MultiscaleGpu {
    gpu: Gpu,
    upsample: Arc<Kernel>,
    enter: Arc<Kernel>,
    /// The correction variants, by [transfers][period test].
    correct: [[Arc<Kernel>; 2]; 2],
    exit: Arc<Kernel>,
    select: Arc<Kernel>,
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
            let atlas = DepthAtlas::new(analysis, set)?;
            let matrix: Vec<u32> = set
                .offset_matrix
                .iter()
                .flat_map(|row| row.map(|v| v as u32))
                .collect();
            let buf = |name: &str, data: &[u32]| {
                GpuBuffer::from_slice(gpu, format!("multiscale {name} set {s}"), data)
            };
            sets.push(GpuSet {
                lookup: buf("lookup", &atlas.lookup)?,
                texels: buf("texels", &atlas.texels)?,
                continued: buf("continued", &atlas.continued)?,
                appearance: buf("appearance", &atlas.appearance)?,
                records: buf("records", &atlas.records)?,
                candidate_texels: buf("candidate texels", &atlas.candidate_texels)?,
                candidate_extras: buf("candidate extras", &atlas.candidate_extras)?,
                candidate_periods: buf("candidate periods", &atlas.candidate_periods)?,
                matrix: buf("matrix", &matrix)?,
                has_reach: atlas.has_reach,
                has_transfer: atlas.has_transfer,
                zero_texel: atlas.texel_count,
            });
        }
        Ok(MultiscaleGpu {
            gpu: gpu.clone(),
            upsample: gpu.kernel(&synth::MULTISCALE_UPSAMPLE)?,
            enter: gpu.kernel(&synth::MULTISCALE_ENTER)?,
            correct: [
                [
                    gpu.kernel(&synth::MULTISCALE_CORRECT_PLAIN)?,
                    gpu.kernel(&synth::MULTISCALE_CORRECT_PERIOD)?,
                ],
                [
                    gpu.kernel(&synth::MULTISCALE_CORRECT_TRANSFERS)?,
                    gpu.kernel(&synth::MULTISCALE_CORRECT)?,
                ],
            ],
            exit: gpu.kernel(&synth::MULTISCALE_EXIT)?,
            select: gpu.kernel(&synth::MULTISCALE_SELECT)?,
            exemplars: GpuBuffer::from_slice(gpu, "multiscale exemplars", &exemplar_words)?,
            sets,
        })
    }

    /// The correction kernel each depth `0..=params.depth()` runs. Transfers can differ from
    /// zero from the first depth whose set has a candidate with one (states start at zero,
    /// upsampling blends them): until then the correction reads none. The period test runs
    /// only where a candidate can fail it.
    pub fn correction_variants(
        &self,
        analysis: &MultiscaleAnalysis,
        params: &MultiscaleParams,
    ) -> Vec<CorrectionVariant> {
        let mut transfers = false;
        (0..=params.depth())
            .map(|t| {
                let set = &self.sets[analysis.superexemplar.set_of(t)];
                transfers |= set.has_transfer;
                CorrectionVariant {
                    transfers,
                    period: set.has_reach && params.period_penalty != 0,
                }
            })
            .collect()
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
        self.synthesize_counted(analysis, params, window, keep_levels)
            .map(|(s, times, _)| (s, times))
    }

    /// [`MultiscaleGpu::synthesize`], also returning per depth how many correction subpasses
    /// ran the period test (the device switches to it from the subpass after a pixel reaches
    /// a level offering candidates it can penalize).
    ///
    /// # Errors
    /// As [`MultiscaleGpu::synthesize`].
    pub fn synthesize_counted(
        &self,
        analysis: &MultiscaleAnalysis,
        params: &MultiscaleParams,
        window: Region,
        keep_levels: bool,
    ) -> SynthResult<(MultiscaleSynthesis, Vec<LevelTimes>, Vec<u32>)> {
        check_multiscale_window(window)?;
        let regions = plan_multiscale(window, &params.passes);
        let depth = params.depth();
        let root = analysis.topology.root;
        let re = &analysis.exemplars[root];
        let mut levels = Vec::new();
        let mut times = Vec::new();
        let mut parent: Option<(Region, GpuBuffer<u32>)> = None;
        let variants = self.correction_variants(analysis, params);
        let words = CONTROL_WORDS * regions.len();
        let control = GpuBuffer::from_slice(&self.gpu, "multiscale control", &vec![0u32; words])?;
        for (t, &region) in regions.iter().enumerate() {
            let set = &self.sets[analysis.superexemplar.set_of(t as u32)];
            let states = GpuBuffer::<u32>::new(
                &self.gpu,
                format!("multiscale states depth {t}"),
                region.pixels() * 5,
            )?;
            let texel = GpuBuffer::<u32>::new(
                &self.gpu,
                format!("multiscale working texels depth {t}"),
                region.pixels(),
            )?;
            let transfer = GpuBuffer::<u32>::new(
                &self.gpu,
                format!("multiscale working transfers depth {t}"),
                region.pixels() * 2,
            )?;
            let variant = variants[t];
            let [plain, tested] = &self.correct[variant.transfers as usize];
            let first_word = CONTROL_WORDS * t;
            let control_t = control.address_at(first_word)?;
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
                let pixels = region.pixels() as u32;
                let enter = MsEnterPush {
                    states: states.address(),
                    texel: texel.address(),
                    transfer: transfer.address(),
                    exemplars: self.exemplars.address(),
                    lookup: set.lookup.address(),
                    control: control_t,
                    pixels,
                    zero_texel: set.zero_texel,
                };
                let k = &self.enter;
                rec.dispatch(k, k.groups_for(pixels as u64), &[], &enter)?;
                for _ in 0..params.passes[t] {
                    for class in CLASSES {
                        let (fx, cx) = class_span(region.origin[0], region.size[0], class[0]);
                        let (fy, cy) = class_span(region.origin[1], region.size[1], class[1]);
                        if cx * cy == 0 {
                            continue;
                        }
                        let push = MsCorrectPush {
                            texel: texel.address(),
                            transfer: transfer.address(),
                            texels: set.texels.address(),
                            continued: set.continued.address(),
                            appearance: set.appearance.address(),
                            records: set.records.address(),
                            cand_texel: set.candidate_texels.address(),
                            cand_extra: set.candidate_extras.address(),
                            cand_period: set.candidate_periods.address(),
                            exemplars: self.exemplars.address(),
                            matrix: set.matrix.address(),
                            control: control_t,
                            size: region.size,
                            first: [fx, fy],
                            count: [cx, cy],
                            k: analysis.k,
                            penalty: params.period_penalty,
                        };
                        let groups = plain.groups_for(cx as u64 * cy as u64);
                        if variant.period {
                            // The device picks the kernel (multiscale_select.comp): the one
                            // not picked gets no workgroups.
                            let select = MsSelectPush {
                                control: control_t,
                                groups,
                            };
                            rec.dispatch(&self.select, [1, 1, 1], &[], &select)?;
                            let (w, tw) = (first_word as u64 + 1, first_word as u64 + 4);
                            rec.dispatch_indirect(plain, &control, w, &[], &push)?;
                            rec.dispatch_indirect(tested, &control, tw, &[], &push)?;
                        } else {
                            rec.dispatch(plain, groups, &[], &push)?;
                        }
                    }
                }
                let exit = MsExitPush {
                    texel: texel.address(),
                    transfer: transfer.address(),
                    states: states.address(),
                    texels: set.texels.address(),
                    pixels,
                };
                let k = &self.exit;
                rec.dispatch(k, k.groups_for(pixels as u64), &[], &exit)?;
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
        let counts = control.read()?;
        let period_subpasses = (0..regions.len())
            .map(|t| counts[CONTROL_WORDS * t + 7])
            .collect();
        Ok((
            MultiscaleSynthesis { window, levels },
            times,
            period_subpasses,
        ))
    }
}
