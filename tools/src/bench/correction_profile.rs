//! `lazysolid bench lazy --profile-correction`: where a request's device time goes. One fixed
//! request (the first mesh at the first resolution, a fresh state keeping every version) runs
//! once per cumulative part of the correction (`CorrectParts`), every dispatch timed by
//! timestamps of its own; the notes give each part's added correction time and, for the whole
//! correction, every kernel's device time and dispatches. A last run visits the voxels in their
//! keys' order instead of grouped (`VisitOrder::Keys`), so that what the grouping gains is the
//! ratio of two runs of one sitting (`docs/lazy.md`, "Where the device time goes").

use lazysolid_compute::gpu::Gpu;
use lazysolid_synth::solid::lazy::{CorrectParts, GpuLazySolid, MemoryPolicy, VisitOrder};

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
    // One request on a fresh state: its triples, report, wall ms, submissions and profile.
    let profiled = |part: CorrectParts, visit: VisitOrder| -> anyhow::Result<_> {
        let mut lazy = state()?;
        lazy.set_policy(MemoryPolicy::Keep);
        lazy.set_correct_parts(part)?;
        lazy.set_visit_order(visit);
        gpu.take_dispatch_profile();
        gpu.profile_dispatches(true);
        let before = gpu.submissions();
        let start = std::time::Instant::now();
        let result = lazy.request(requested);
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        let submissions = gpu.submissions().since(before);
        gpu.profile_dispatches(false);
        let (triples, report) = result?;
        let profile = gpu.take_dispatch_profile();
        let correct = profile
            .iter()
            .find(|k| k.kernel.ends_with("lazy_correct.comp"))
            .map_or(0.0, |k| k.device_ns * 1e-6);
        Ok((triples, report, wall_ms, submissions, profile, correct))
    };
    let mut previous = 0.0;
    let mut grouped = None;
    for part in CorrectParts::PROFILE {
        let (triples, report, wall_ms, submissions, profile, correct) =
            profiled(part, VisitOrder::Grouped)?;
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
            grouped = Some((triples, correct));
        }
    }
    let (grouped_triples, grouped_ms) = grouped.expect("the profile ends with every part");
    let (triples, .., correct) = profiled(CorrectParts::All, VisitOrder::Keys)?;
    anyhow::ensure!(
        triples == grouped_triples,
        "{case}: the correction in key order gave other triples than grouped"
    );
    notes.push((
        format!("{case}: voxels in key order: lazy_correct device ms"),
        correct,
    ));
    notes.push((
        format!("{case}: key order / grouped, lazy_correct device time"),
        correct / grouped_ms.max(f64::MIN_POSITIVE),
    ));
    Ok(())
}
