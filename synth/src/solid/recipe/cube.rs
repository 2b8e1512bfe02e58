//! A box of the volume synthesized with the figures a run reports about it.

use super::PreparedSolid;
use crate::solid::{
    candidate_slab, level_schedules, plan_levels, triple_consistency, SolidSynthesis,
    TripleConsistency, VolumeBox,
};
use crate::SynthResult;
use lazysolid_compute::gpu::Gpu;
use std::time::Instant;

/// A synthesized box and what `lazysolid solid` and `bench solid` report about it.
pub struct SolidCube {
    /// The synthesis: the window's triples and every level's.
    pub synthesis: SolidSynthesis,
    /// Colours of the window, x fastest.
    pub colours: Vec<[u8; 3]>,
    /// Wall time of the GPU synthesis (kernels made before it), seconds.
    pub synthesis_s: f64,
    /// Peak GPU memory of the synthesis, bytes.
    pub peak_bytes: u64,
    /// Voxels computed (upsampled and jittered) over all levels, window and padding.
    pub voxels: u64,
    /// Voxel updates of all correction subpasses over all levels.
    pub voxel_updates: u64,
    /// The candidate slab picture: width, height, pixels.
    pub slab: (u32, u32, Vec<[u8; 3]>),
    /// Fallbacks of the coherence filter, over all levels.
    pub fallbacks: u64,
    /// How consistent the window's triples are.
    pub consistency: TripleConsistency,
}

impl PreparedSolid {
    /// Synthesizes `window` with the windowed synthesizer; `on_level` is called after each
    /// level.
    ///
    /// # Errors
    /// A window out of range or that does not fit the device.
    pub fn cube(
        &self,
        gpu: &Gpu,
        window: VolumeBox,
        on_level: &mut dyn FnMut(u32),
    ) -> SynthResult<SolidCube> {
        let synth = self.synthesizer(gpu)?;
        let start = Instant::now();
        let (synthesis, _) = synth.synthesize(
            &self.analysis,
            &self.candidates,
            &self.params,
            window,
            false,
            on_level,
        )?;
        let synthesis_s = start.elapsed().as_secs_f64();
        let exemplars = self.exemplars();
        let colours = synthesis.colours(exemplars);
        let schedules = level_schedules(&self.params);
        let plan = plan_levels(window, &schedules);
        Ok(SolidCube {
            peak_bytes: synth.peak_bytes(window, &schedules),
            voxels: plan.iter().map(|p| p.region.voxels() as u64).sum(),
            voxel_updates: plan.iter().map(|p| p.updates()).sum(),
            slab: candidate_slab(exemplars, &self.candidates, 4),
            fallbacks: self.candidates.reports.iter().map(|r| r.fallbacks).sum(),
            consistency: triple_consistency(exemplars, &self.candidates, &synthesis),
            synthesis,
            colours,
            synthesis_s,
        })
    }
}
