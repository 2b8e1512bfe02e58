//! `lazysolid bench cuts`: every plane cut and the fracture timed, one row each.

use crate::support::{lazysolid, terra_square, BenchRun};

/// `lazysolid bench cuts` times every plane cut and the fracture as one row each, with the
/// voxels the caps need, the new ones synthesized, the store's growth and the measured
/// temporary memory on the device and the host, its device time, the rest and its host
/// waits, and per level the versions it computed.
#[test]
fn bench_cuts_times_every_cut_and_fracture() {
    let out = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "cuts",
                "--mesh",
                "elephant",
                "--voxel-res",
                "32",
                "--pieces",
                "4",
            ])
            .arg("--exemplar")
            .arg(&exemplar)
            .env("LAZYSOLID_CACHE_DIR", dir.path().join("cache")),
        out.path(),
        &[
            "32³ plane cut 1 normal [0.0, 1.0, 0.0]: new voxels",
            "32³ plane cut 4 normal [1.0, 1.0, 0.4]: wall ms",
            "32³ fracture 4 pieces: voxel versions synthesized",
            "32³ fracture 4 pieces: store MB after",
            "32³ fracture 4 pieces: host heap MB at peak above before",
            "32³ fracture 4 pieces: temporary MB, device + host",
            "lazy request + insert (wall)",
            "device, every submission",
            "32³ fracture 4 pieces: host waits (submissions)",
            "32³ fracture 4 pieces: voxel versions per new voxel",
            "thesis (2008 GPU): 8 ms",
        ],
    );
    let json = bench.json();
    assert!(json["rows"].as_array().is_some_and(|r| r.len() == 15));
    // The memory figures are measured: a cut that synthesizes allocates device buffers and
    // host lists, and frees its temporaries.
    let note = |k: &str| {
        json["derived"][k]
            .as_f64()
            .unwrap_or_else(|| panic!("{k}: {}", json["derived"]))
    };
    // Per level, the kept state after the outer surface: its levels add up to the state's
    // bytes, less the per-level records the kernels read.
    let levels: Vec<f64> = (0..)
        .map_while(|l| {
            json["derived"][format!("32³: level {l} state MB after the outer surface")].as_f64()
        })
        .collect();
    let state = note("32³: state MB after the outer surface");
    let sum: f64 = levels.iter().sum();
    assert!(
        levels.len() > 1 && sum > 0.0 && sum <= state && state - sum < 0.01,
        "{levels:?} against {state} MB"
    );
    let case = "32³ fracture 4 pieces";
    assert!(note(&format!("{case}: voxel versions synthesized")) > 0.0);
    assert!(note(&format!("{case}: device MB at peak above before")) > 0.0);
    assert!(note(&format!("{case}: host heap MB at peak above before")) > 0.0);
    assert!(note(&format!("{case}: device temporary MB (peak - kept)")) > 0.0);
    // Device time comes from timestamps around every submission of the cut: positive, and
    // within the cut's wall time.
    let device = note(&format!("{case}: device ms, every submission"));
    let wall = note(&format!("{case}: wall ms"));
    assert!(
        device > 0.0 && device <= wall,
        "device {device} ms, wall {wall} ms"
    );
    assert!(note(&format!("{case}: host waits (submissions)")) >= 1.0);
    // Per level, the versions the cut computed add up to its total, and the finest level
    // gained voxels.
    let per_level: Vec<(f64, f64)> = (0..)
        .map_while(|l| {
            let computed =
                json["derived"][format!("{case}: level {l} versions computed")].as_f64()?;
            let new = note(&format!("{case}: level {l} voxels new to the state"));
            Some((computed, new))
        })
        .collect();
    assert!(per_level.len() > 1, "{per_level:?}");
    assert_eq!(
        per_level.iter().map(|l| l.0).sum::<f64>(),
        note(&format!("{case}: voxel versions synthesized"))
    );
    assert!(per_level.last().is_some_and(|l| l.1 > 0.0), "{per_level:?}");
}
