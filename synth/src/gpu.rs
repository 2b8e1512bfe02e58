//! The GPU synthesizer: the analysis uploaded once, then per level one submission of the
//! upsample-and-jitter kernel and `4 × passes` correction subpasses.

use super::analysis::ExemplarAnalysis;
use super::cpu::CLASSES;
use super::error::SynthResult;
use super::neighbourhood::pack_i8_words;
use super::params::SynthParams;
use super::period::period_reach;
use super::plan::{plan_regions, Region};
use super::synthesis::{check_window, LevelCoords, Synthesis};
use crate::kernels::synth;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct UpsamplePush<'a> {
        parent: DeviceAddress<'a>,
        coords: DeviceAddress<'a>,
        origin: [i32; 2],
        size: [u32; 2],
        parent_origin: [i32; 2],
        parent_size: [u32; 2],
        origin_mod: [u32; 2],
        exemplar: [u32; 2],
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
        coords: DeviceAddress<'a>,
        appearance: DeviceAddress<'a>,
        neighbourhoods: DeviceAddress<'a>,
        coherence: DeviceAddress<'a>,
        origin: [i32; 2],
        size: [u32; 2],
        first: [u32; 2],
        count: [u32; 2],
        exemplar: [u32; 2],
        spacing: u32,
        k: u32,
        reach: [u32; 2],
        penalty: u32,
    }
}

/// Device time of one level's kernels, from GPU timestamps: what a profile of the synthesis
/// needs to tell the per-pixel upsampling from the correction passes that dominate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelTimes {
    /// Pyramid level (0 is the coarsest).
    pub level: u32,
    /// Pixels of the region computed at this level (window plus padding).
    pub pixels: u64,
    /// The upsample-and-jitter dispatch, in milliseconds.
    pub upsample_ms: f64,
    /// All correction subpasses of the level, in milliseconds.
    pub correct_ms: f64,
}

/// One level's analysis on the GPU.
struct GpuLevel {
    spacing: u32,
    appearance: GpuBuffer<u32>,
    neighbourhoods: GpuBuffer<u32>,
    coherence: GpuBuffer<u32>,
}

/// An exemplar analysis on the GPU, ready to synthesize any number of windows.
pub struct GpuSynthesizer {
    gpu: Gpu,
    upsample: Arc<Kernel>,
    correct: Arc<Kernel>,
    levels: Vec<GpuLevel>,
    width: u32,
    height: u32,
    k: u32,
}

/// First interior local position of parity `class` along one axis, and how many there are.
pub(crate) fn class_span(origin: i32, size: u32, class: i32) -> (u32, u32) {
    let first = 1 + ((class - (origin + 1)) & 1) as u32;
    let last = size as i64 - 2;
    if (first as i64) > last {
        (first, 0)
    } else {
        (first, ((last - first as i64) / 2 + 1) as u32)
    }
}

impl GpuSynthesizer {
    /// Builds the kernels and uploads `analysis`.
    ///
    /// # Errors
    /// A GPU failure (kernel creation, allocation or upload).
    pub fn new(gpu: &Gpu, analysis: &ExemplarAnalysis) -> SynthResult<GpuSynthesizer> {
        let levels = analysis
            .levels
            .iter()
            .enumerate()
            .map(|(l, lv)| {
                let words = pack_i8_words(lv.appearance.as_flattened());
                let records = pack_i8_words(lv.neighbourhoods.as_flattened());
                Ok(GpuLevel {
                    spacing: lv.spacing,
                    appearance: GpuBuffer::from_slice(
                        gpu,
                        format!("synth appearance level {l}"),
                        &words,
                    )?,
                    neighbourhoods: GpuBuffer::from_slice(
                        gpu,
                        format!("synth neighbourhoods level {l}"),
                        &records,
                    )?,
                    coherence: GpuBuffer::from_slice(
                        gpu,
                        format!("synth coherence level {l}"),
                        &lv.coherence,
                    )?,
                })
            })
            .collect::<SynthResult<Vec<_>>>()?;
        Ok(GpuSynthesizer {
            gpu: gpu.clone(),
            upsample: gpu.kernel(&synth::UPSAMPLE_JITTER)?,
            correct: gpu.kernel(&synth::CORRECT)?,
            levels,
            width: analysis.width,
            height: analysis.height,
            k: analysis.k,
        })
    }

    /// Number of pyramid levels.
    pub fn levels(&self) -> u32 {
        self.levels.len() as u32
    }

    /// Synthesizes `window` of the finest level. `keep_levels` reads every level back (for
    /// tests and figures), otherwise only the finest; `on_level` is called after each level.
    ///
    /// # Errors
    /// A window or parameter set that does not fit, or a GPU failure.
    pub fn synthesize(
        &self,
        analysis: &ExemplarAnalysis,
        params: &SynthParams,
        window: Region,
        keep_levels: bool,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<Synthesis> {
        self.synthesize_timed(analysis, params, window, keep_levels, on_level)
            .map(|(synthesis, _)| synthesis)
    }

    /// [`GpuSynthesizer::synthesize`] that also reports the device time of every level's
    /// kernels (GPU timestamps around the dispatches; submission, waiting and read-back are
    /// not included), so that benchmarks time the GPU work alone and can tell which kernel
    /// dominates.
    ///
    /// # Errors
    /// As [`GpuSynthesizer::synthesize`].
    pub fn synthesize_timed(
        &self,
        analysis: &ExemplarAnalysis,
        params: &SynthParams,
        window: Region,
        keep_levels: bool,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<(Synthesis, Vec<LevelTimes>)> {
        check_window(analysis, params, window)?;
        let finest = self.levels.len() as u32 - 1;
        let regions = plan_regions(window, &params.passes);
        let exemplar = [self.width, self.height];
        let mut levels = Vec::new();
        let mut times = Vec::with_capacity(regions.len());
        let mut parent: Option<(Region, GpuBuffer<u32>)> = None;
        for (l, &region) in regions.iter().enumerate() {
            let lv = &self.levels[l];
            let reach = period_reach(lv.spacing, self.width, self.height);
            let coords = GpuBuffer::<u32>::new(
                &self.gpu,
                format!("synth coords level {l}"),
                region.pixels(),
            )?;
            let push = UpsamplePush {
                parent: parent
                    .as_ref()
                    .map_or(coords.address(), |(_, b)| b.address()),
                coords: coords.address(),
                origin: region.origin,
                size: region.size,
                parent_origin: parent.as_ref().map_or([0; 2], |(r, _)| r.origin),
                parent_size: parent.as_ref().map_or([0; 2], |(r, _)| r.size),
                origin_mod: [0, 1].map(|a| region.origin[a].rem_euclid(exemplar[a] as i32) as u32),
                exemplar,
                spacing: lv.spacing,
                level: l as u32,
                seed: params.seed,
                strength: params.jitter[l],
                has_parent: parent.is_some() as u32,
            };
            let ((), stamps) = self.gpu.submit_timed(|rec| {
                rec.timestamp()?;
                let k = &self.upsample;
                rec.dispatch(k, k.groups_for(region.pixels() as u64), &[], &push)?;
                rec.timestamp()?;
                for _ in 0..params.passes[l] {
                    for class in CLASSES {
                        let (fx, cx) = class_span(region.origin[0], region.size[0], class[0]);
                        let (fy, cy) = class_span(region.origin[1], region.size[1], class[1]);
                        if cx * cy == 0 {
                            continue;
                        }
                        let push = CorrectPush {
                            coords: coords.address(),
                            appearance: lv.appearance.address(),
                            neighbourhoods: lv.neighbourhoods.address(),
                            coherence: lv.coherence.address(),
                            origin: region.origin,
                            size: region.size,
                            first: [fx, fy],
                            count: [cx, cy],
                            exemplar,
                            spacing: lv.spacing,
                            k: self.k,
                            reach,
                            penalty: if reach == [0, 0] {
                                0
                            } else {
                                params.period_penalty
                            },
                        };
                        let k = &self.correct;
                        rec.dispatch(k, k.groups_for(cx as u64 * cy as u64), &[], &push)?;
                    }
                }
                rec.timestamp()
            })?;
            times.push(LevelTimes {
                level: l as u32,
                pixels: region.pixels() as u64,
                upsample_ms: (stamps[1] - stamps[0]) * 1e-6,
                correct_ms: (stamps[2] - stamps[1]) * 1e-6,
            });
            if keep_levels || l as u32 == finest {
                levels.push(LevelCoords {
                    region,
                    coords: coords.read()?,
                });
            }
            on_level(l as u32);
            parent = Some((region, coords));
        }
        Ok((Synthesis { window, levels }, times))
    }
}
