//! The one analysis and candidate step, and the synthesizers built from it.

use super::SolidSources;
use crate::cache::{CacheOutcome, DiskCache};
use crate::solid::lazy::{GpuLazySolid, MemoryPolicy};
use crate::solid::{
    candidates_cached, CandidateBuilder, GpuSolidSynthesizer, SolidAnalysis, SolidCandidates,
    SolidExemplars, SolidRelief,
};
use crate::{SynthParams, SynthResult};
use lazysolid_compute::gpu::Gpu;
use std::time::Instant;

/// A recipe's exemplars analysed, with their candidates and the synthesizer's parameters:
/// what every synthesizer of the recipe reads.
pub struct PreparedSolid {
    /// The exemplars and what was done to them.
    pub sources: SolidSources,
    /// Their analysis.
    pub analysis: SolidAnalysis,
    /// Their candidates, computed or read from the cache.
    pub candidates: SolidCandidates,
    /// The synthesizer's parameters for the exemplars' pyramid.
    pub params: SynthParams,
    /// What the candidate cache did.
    pub cached: CacheOutcome,
    /// Where the candidates were (or, on a cache hit, would have been) computed.
    pub builder: CandidateBuilder,
    /// Wall time of the CPU analysis, seconds.
    pub analysis_s: f64,
    /// Wall time of the candidates (computed or read back), seconds.
    pub candidates_s: f64,
}

impl SolidSources {
    /// Analyses the exemplars and computes their candidates through `cache` (`None`: no
    /// cache), on the recipe's builder. `on_step(done, total)` follows the candidate steps:
    /// the sets per level, then the usage balance's pilot per level when the balance is on.
    ///
    /// # Errors
    /// A schedule that does not fit the pyramid, candidate parameters out of range, or a
    /// device failure.
    pub fn prepare(
        &self,
        gpu: &Gpu,
        cache: Option<&DiskCache>,
        on_step: &mut dyn FnMut(u32, u32),
    ) -> SynthResult<PreparedSolid> {
        let recipe = &self.recipe;
        let start = Instant::now();
        let analysis = self.analyze();
        let analysis_s = start.elapsed().as_secs_f64();
        let levels = analysis.levels.len() as u32;
        // The parameters first: a schedule that does not fit fails before the precompute.
        let params = recipe.synth_params(levels)?;
        recipe.candidates.check()?;
        let start = Instant::now();
        let total = levels * if recipe.candidates.balance > 0 { 2 } else { 1 };
        let mut done = 0;
        let (candidates, cached) =
            candidates_cached(&self.exemplars, &recipe.candidates, cache, || {
                recipe
                    .builder
                    .compute(gpu, &analysis, &recipe.candidates, &mut |_| {
                        done += 1;
                        on_step(done, total)
                    })
            })?;
        Ok(PreparedSolid {
            sources: self.clone(),
            analysis,
            candidates,
            params,
            cached,
            builder: recipe.builder.resolve(gpu),
            analysis_s,
            candidates_s: start.elapsed().as_secs_f64(),
        })
    }
}

impl PreparedSolid {
    /// The exemplars the synthesis uses.
    pub fn exemplars(&self) -> &SolidExemplars {
        &self.sources.exemplars
    }

    /// The windowed synthesizer: any box of the unbounded volume, in one call
    /// ([`PreparedSolid::cube`] runs it with the figures a report wants).
    ///
    /// # Errors
    /// Device allocation failures.
    pub fn synthesizer(&self, gpu: &Gpu) -> SynthResult<GpuSolidSynthesizer> {
        GpuSolidSynthesizer::new(gpu, &self.analysis, &self.candidates)
    }

    /// The lazy synthesizer at equivalent resolution `resolution` (the texture is
    /// `resolution`³ voxels over the unit cube), keeping what `policy` says between requests,
    /// with the relief channel when the recipe asks for it.
    ///
    /// # Errors
    /// A resolution out of range or device allocation failures.
    pub fn lazy(
        &self,
        gpu: &Gpu,
        resolution: u32,
        policy: MemoryPolicy,
    ) -> SynthResult<GpuLazySolid> {
        let exemplars = self.exemplars();
        let mut state = GpuLazySolid::new(
            gpu,
            exemplars,
            &self.analysis,
            &self.candidates,
            &self.params,
            resolution,
        )?;
        state.set_policy(policy);
        if self.sources.recipe.relief {
            state.set_relief(exemplars, Some(SolidRelief::of(exemplars)))?;
        }
        Ok(state)
    }
}
