//! `lazysolid bench lazy --profile-correction`: where a request's device time goes. One fixed
//! request (the first mesh at the first resolution, a fresh state keeping every version) runs
//! once per cumulative part of the correction (`CorrectParts`), every dispatch timed by
//! timestamps of its own; the notes give each part's added correction time and, for the whole
//! correction, every kernel's device time and dispatches.

use lazysolid_compute::gpu::Gpu;
use lazysolid_synth::solid::lazy::{CorrectParts, GpuLazySolid, MemoryPolicy};

/// Profiles the request of `requested` voxels on fresh states from `state`, noting under
/// `case`.
pub(super) fn run(
    gpu: &Gpu,
    state: &dyn Fn() -> anyhow::Result<GpuLazySolid>,
    requested: &[[i32; 3]],
    case: &str,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let case = format!("{case}, correction profile (fresh state, keep)");
    let mut previous = 0.0;
    for part in CorrectParts::PROFILE {
        let mut lazy = state()?;
        lazy.set_policy(MemoryPolicy::Keep);
        lazy.set_correct_parts(part)?;
        gpu.take_dispatch_profile();
        gpu.profile_dispatches(true);
        let before = gpu.submissions();
        let start = std::time::Instant::now();
        let result = lazy.request(requested);
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        let submissions = gpu.submissions().since(before);
        gpu.profile_dispatches(false);
        let (_, report) = result?;
        let profile = gpu.take_dispatch_profile();
        let correct = profile
            .iter()
            .find(|k| k.kernel.ends_with("lazy_correct.comp"))
            .map_or(0.0, |k| k.device_ns * 1e-6);
        notes.push((
            format!("{case}: up to {}: lazy_correct device ms", part.name()),
            correct,
        ));
        notes.push((
            format!("{case}: {} adds ms", part.name()),
            correct - previous,
        ));
        previous = correct;
        if part == CorrectParts::All {
            let versions: u64 = report.computed.iter().sum();
            notes.push((format!("{case}: voxel versions computed"), versions as f64));
            notes.push((
                format!("{case}: lazy_correct µs per version"),
                1e3 * correct / versions.max(1) as f64,
            ));
            notes.push((format!("{case}: wall ms (profiled)"), wall_ms));
            notes.push((
                format!("{case}: device ms, every submission (profiled)"),
                submissions.device_ms(),
            ));
            notes.push((
                format!("{case}: host waits (submissions)"),
                submissions.waits as f64,
            ));
            for k in &profile {
                let what = format!("{case}: kernel {}", k.kernel);
                notes.push((format!("{what} device ms"), k.device_ns * 1e-6));
                notes.push((format!("{what} dispatches"), k.dispatches as f64));
            }
        }
    }
    Ok(())
}
