//! `lazysolid bench normalmaps`: the three normal-map filters against a many-sample reference
//! on the V-groove scene, the vMF fit's time and memory, and bad arguments refused.

use crate::support::{lazysolid, repo, run, BenchRun};

/// Quality rows for each filter and sample count with the reference's noise floor, the fit rows
/// and the memory notes, the pictures and the chart; at this small size the V-groove's false
/// highlight already makes plain MIP the worst filter in the far field.
#[test]
fn bench_normalmaps_scores_the_filters_and_times_the_fit() {
    let out = tempfile::tempdir().unwrap();
    let scene = repo("scenes/normal-maps/v-groove.toml");
    let bench = BenchRun::new(
        lazysolid().args([
            "bench",
            "normalmaps",
            "--scenes",
            scene.to_str().unwrap(),
            "--res",
            "64x48",
            "--spp",
            "4",
            "--reference-spp",
            "32",
            "--fit-sizes",
            "16",
            "--lobes",
            "2,4",
            "--warmup",
            "0",
            "--runs",
            "1",
        ]),
        out.path(),
        &[
            "far-field pixels",
            "plain MIP",
            "vMF",
            "vMF fit 16² J=4",
            "quality table",
        ],
    );
    let json = bench.json();
    assert_eq!(json["rows"].as_array().map(Vec::len), Some(4));
    assert_eq!(
        json["derived"]["16² vMF J=4 bytes (f32 α, α·r)"].as_f64(),
        Some(((256 + 64 + 16 + 4 + 1) * 4 * 16) as f64)
    );
    let ratio = json["derived"]["v-groove 4 spp: far error plain MIP / vMF"]
        .as_f64()
        .unwrap();
    assert!(ratio > 1.0, "plain MIP / vMF far error {ratio}");
    let names = bench.figure_names();
    for f in [
        "quality.csv",
        "v-groove-reference.png",
        "v-groove-vmf-4spp.png",
        "v-groove-plain-mip-4spp.png",
        "v-groove-unfiltered-4spp.png",
        "v-groove-far-error.png",
    ] {
        assert!(names.iter().any(|n| n == f), "missing {f} in {names:?}");
    }
    let quality = std::fs::read_to_string(bench.figures().join("quality.csv")).unwrap();
    assert_eq!(quality.lines().count(), 1 + 1 + 3);

    for (args, needle) in [
        (&["--lobes", "9"][..], "1..=8"),
        (&["--fit-sizes", "12"][..], "power of two"),
        (&["--far-distance", "0"][..], "positive"),
        (
            &["--scenes", "scenes/default.toml"][..],
            "no material with a normal_map",
        ),
    ] {
        let (ok, _, err) = run(lazysolid()
            .args(["bench", "normalmaps"])
            .args(args)
            .current_dir(repo("")));
        assert!(!ok && err.contains(needle), "{args:?}: {err}");
    }
}
