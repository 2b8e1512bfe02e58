//! The candidate construction on the GPU: `strip_search.comp`, `triples.comp` and
//! `coherence.comp` per level, driven by the same iteration loop as the CPU reference
//! (`candidates.rs`), with which it agrees exactly.

use super::analysis::{SolidAnalysis, SolidLevel};
use super::candidates::{
    build_levels, crossbar_pair, others, CandidateParams, CandidateSets, SearchKey, SolidCandidates,
};
use super::loop_budget::{items_per_dispatch, loop_cost, LOOP_BUDGET};
use super::roles::ROLES;
use crate::kernels::synth_solid;
use crate::{SynthError, SynthResult};
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct SearchPush<'a> {
        query: DeviceAddress<'a>,
        target: DeviceAddress<'a>,
        pixels: DeviceAddress<'a>,
        distances: DeviceAddress<'a>,
        shift: u32,
        query_axis: u32,
        target_axis: u32,
        strip: u32,
        spacing: u32,
        s: u32,
        first_target: u32,
        target_count: u32,
    }
}

/// Target pixels one strip-search dispatch compares: each costs the outer loop's pass, the
/// strip's samples and a sift down the max-heap of the `S` best; the query strip is loaded and
/// the heap loaded and stored once per dispatch, and the last one heap-sorts it
/// (`strip_search.comp`).
fn targets_per_dispatch(budget: u32, params: &CandidateParams) -> SynthResult<u32> {
    let sift = loop_cost(params.s.ilog2());
    let per_target = 1 + loop_cost(params.strip) + sift;
    let overhead = 1 + loop_cost(params.strip) + 2 * loop_cost(params.s) + params.s * (1 + sift);
    items_per_dispatch(budget, per_target, overhead)
}

/// Rows `i` of the `S × S` crossbar pairs one ranking dispatch takes: a row loads one strip
/// and, per `j`, compares a strip and may sift a new entry down the kept max-heap
/// (`triples.comp`); the heap is loaded and stored, and the last dispatch heap-sorts it and
/// writes the kept triples.
fn rows_per_dispatch(budget: u32, params: &CandidateParams) -> SynthResult<u32> {
    let kept = params.kept() as u32;
    let sift = loop_cost(kept.ilog2());
    let per_j = 1 + loop_cost(params.strip) + sift;
    let per_row = 1 + loop_cost(params.strip) + 1 + params.s * per_j;
    let overhead = 1 + 2 * loop_cost(kept) + kept * (1 + sift) + kept * loop_cost(3);
    items_per_dispatch(budget, per_row, overhead)
}

/// Workgroup width of the coherence filter (one workgroup per pixel).
const COHERENCE_WORKGROUP: u32 = 64;

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct TriplesPush<'a> {
        colours1: DeviceAddress<'a>,
        colours2: DeviceAddress<'a>,
        m1_pixels: DeviceAddress<'a>,
        m1_distances: DeviceAddress<'a>,
        m2_pixels: DeviceAddress<'a>,
        m2_distances: DeviceAddress<'a>,
        triples: DeviceAddress<'a>,
        errors: DeviceAddress<'a>,
        keys: DeviceAddress<'a>,
        counts: DeviceAddress<'a>,
        shift: u32,
        axis1: u32,
        axis2: u32,
        strip: u32,
        spacing: u32,
        s: u32,
        kept: u32,
        role1: u32,
        role2: u32,
        first_row: u32,
        rows: u32,
    }
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct CoherencePush<'a> {
        in_triples: DeviceAddress<'a>,
        in_errors: DeviceAddress<'a>,
        in_counts: DeviceAddress<'a>,
        out_triples: DeviceAddress<'a>,
        out_errors: DeviceAddress<'a>,
        out_counts: DeviceAddress<'a>,
        fallbacks: DeviceAddress<'a>,
        shift: u32,
        spacing: u32,
        slots: u32,
        role1: u32,
        role2: u32,
        first_pixel: u32,
    }
}

/// Strip matches on the GPU.
struct Matches {
    pixels: GpuBuffer<u32>,
    distances: GpuBuffer<u32>,
}

/// The candidate kernels of one device.
pub struct GpuCandidates {
    gpu: Gpu,
    search: Arc<Kernel>,
    triples: Arc<Kernel>,
    coherence: Arc<Kernel>,
    budget: u32,
}

impl GpuCandidates {
    /// Builds the kernels.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn new(gpu: &Gpu) -> SynthResult<GpuCandidates> {
        Ok(GpuCandidates {
            gpu: gpu.clone(),
            search: gpu.kernel(&synth_solid::STRIP_SEARCH)?,
            triples: gpu.kernel(&synth_solid::TRIPLES)?,
            coherence: gpu.kernel_with(&synth_solid::COHERENCE, COHERENCE_WORKGROUP, &[])?,
            budget: LOOP_BUDGET,
        })
    }

    /// The same kernels planned to `budget` loop iterations per dispatch instead of
    /// [`LOOP_BUDGET`]: a smaller budget splits every search into more dispatches with the
    /// same result (how the tests exercise the folding of dispatches on small exemplars).
    ///
    /// # Errors
    /// A budget above [`LOOP_BUDGET`] (checked when computing, against the parameters), or a
    /// GPU failure.
    pub fn with_loop_budget(gpu: &Gpu, budget: u32) -> SynthResult<GpuCandidates> {
        Ok(GpuCandidates {
            budget,
            ..GpuCandidates::new(gpu)?
        })
    }

    /// The candidates of every level of `analysis`; `on_level` is called after each level.
    ///
    /// # Errors
    /// Parameters out of range, or a GPU failure.
    pub fn compute(
        &self,
        analysis: &SolidAnalysis,
        params: &CandidateParams,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<SolidCandidates> {
        let m = analysis.side;
        let shift = m.ilog2();
        let pixels = (m * m) as usize;
        build_levels(
            analysis,
            params,
            on_level,
            |level| {
                (0..ROLES)
                    .map(|r| {
                        GpuBuffer::from_slice(
                            &self.gpu,
                            format!("solid colours spacing {} role {r}", level.spacing),
                            &level.roles[r].colours,
                        )
                    })
                    .collect::<Result<Vec<GpuBuffer<u32>>, _>>()
                    .map_err(SynthError::from)
            },
            |colours, level, k| self.search(level, colours, k, shift, params),
            |colours, level, e, m1, m2| self.rank(level, colours, e, m1, m2, shift, params),
            |_, level, s, e| self.coherence_step(s, e, level.spacing, shift, pixels),
        )
    }

    fn search(
        &self,
        level: &SolidLevel,
        colours: &[GpuBuffer<u32>],
        k: SearchKey,
        shift: u32,
        params: &CandidateParams,
    ) -> SynthResult<Matches> {
        let pixels = 1usize << (2 * shift);
        let n = pixels * params.s as usize;
        let found = Matches {
            pixels: GpuBuffer::new(&self.gpu, "solid strip matches", n)?,
            distances: GpuBuffer::new(&self.gpu, "solid strip distances", n)?,
        };
        let mut push = SearchPush {
            query: colours[k.query].address(),
            target: colours[k.target].address(),
            pixels: found.pixels.address(),
            distances: found.distances.address(),
            shift,
            query_axis: k.query_axis as u32,
            target_axis: k.target_axis as u32,
            strip: params.strip,
            spacing: level.spacing,
            s: params.s,
            first_target: 0,
            target_count: 0,
        };
        let chunk = targets_per_dispatch(self.budget, params)?;
        self.gpu.submit(|rec| {
            let kernel = &self.search;
            for first in (0..pixels as u32).step_by(chunk as usize) {
                push.first_target = first;
                push.target_count = chunk.min(pixels as u32 - first);
                rec.dispatch(kernel, kernel.groups_for(pixels as u64), &[], &push)?;
            }
            Ok(())
        })?;
        Ok(found)
    }

    #[allow(clippy::too_many_arguments)]
    fn rank(
        &self,
        level: &SolidLevel,
        colours: &[GpuBuffer<u32>],
        e: usize,
        m1: &Matches,
        m2: &Matches,
        shift: u32,
        params: &CandidateParams,
    ) -> SynthResult<CandidateSets> {
        let pixels = 1usize << (2 * shift);
        let kept = params.kept();
        let triples = GpuBuffer::<[u32; 3]>::new(&self.gpu, "solid triples", pixels * kept)?;
        let errors = GpuBuffer::<u32>::new(&self.gpu, "solid crossbar errors", pixels * kept)?;
        let keys = GpuBuffer::<u32>::new(&self.gpu, "solid crossbar keys", pixels * kept)?;
        let counts = GpuBuffer::<u32>::new(&self.gpu, "solid candidate counts", pixels)?;
        let ([f1, f2], [a1, a2]) = crossbar_pair(e);
        let mut push = TriplesPush {
            colours1: colours[f1].address(),
            colours2: colours[f2].address(),
            m1_pixels: m1.pixels.address(),
            m1_distances: m1.distances.address(),
            m2_pixels: m2.pixels.address(),
            m2_distances: m2.distances.address(),
            triples: triples.address(),
            errors: errors.address(),
            keys: keys.address(),
            counts: counts.address(),
            shift,
            axis1: a1 as u32,
            axis2: a2 as u32,
            strip: params.strip,
            spacing: level.spacing,
            s: params.s,
            kept: kept as u32,
            role1: f1 as u32,
            role2: f2 as u32,
            first_row: 0,
            rows: 0,
        };
        let rows = rows_per_dispatch(self.budget, params)?;
        self.gpu.submit(|rec| {
            let kernel = &self.triples;
            for first in (0..params.s).step_by(rows as usize) {
                push.first_row = first;
                push.rows = rows;
                rec.dispatch(kernel, kernel.groups_for(pixels as u64), &[], &push)?;
            }
            Ok(())
        })?;
        Ok(CandidateSets {
            slots: kept,
            triples: triples.read()?,
            errors: errors.read()?,
            counts: counts.read()?,
        })
    }

    fn coherence_step(
        &self,
        sets: &CandidateSets,
        e: usize,
        spacing: u32,
        shift: u32,
        pixels: usize,
    ) -> SynthResult<(CandidateSets, u64)> {
        let g = &self.gpu;
        let input = (
            GpuBuffer::from_slice(g, "solid coherence triples in", &sets.triples)?,
            GpuBuffer::from_slice(g, "solid coherence errors in", &sets.errors)?,
            GpuBuffer::from_slice(g, "solid coherence counts in", &sets.counts)?,
        );
        let output = (
            GpuBuffer::<[u32; 3]>::zeroed(g, "solid coherence triples out", sets.triples.len())?,
            GpuBuffer::<u32>::zeroed(g, "solid coherence errors out", sets.errors.len())?,
            GpuBuffer::<u32>::new(g, "solid coherence counts out", pixels)?,
        );
        let fallbacks = GpuBuffer::<u32>::new(g, "solid coherence fallbacks", pixels)?;
        let [f1, f2] = others(e);
        let mut push = CoherencePush {
            in_triples: input.0.address(),
            in_errors: input.1.address(),
            in_counts: input.2.address(),
            out_triples: output.0.address(),
            out_errors: output.1.address(),
            out_counts: output.2.address(),
            fallbacks: fallbacks.address(),
            shift,
            spacing,
            slots: sets.slots as u32,
            role1: f1 as u32,
            role2: f2 as u32,
            first_pixel: 0,
        };
        // One workgroup per pixel, in as many dispatches as the device's group count needs.
        let most = g.info().max_workgroup_count as usize;
        g.submit(|rec| {
            let kernel = &self.coherence;
            for first in (0..pixels).step_by(most) {
                push.first_pixel = first as u32;
                let groups = (pixels - first).min(most) as u32;
                rec.dispatch(kernel, [groups, 1, 1], &[], &push)?;
            }
            Ok(())
        })?;
        let fell_back = fallbacks.read()?.iter().map(|&f| f as u64).sum();
        Ok((
            CandidateSets {
                slots: sets.slots,
                triples: output.0.read()?,
                errors: output.1.read()?,
                counts: output.2.read()?,
            },
            fell_back,
        ))
    }
}
