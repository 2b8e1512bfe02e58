//! `lazysolid bench synth`: 2D synthesis against texture-synthesis (times, quality over seeds,
//! side-by-side images), and missing exemplars and bad sizes refused.

use crate::support::{lazysolid, repo, run, BenchRun};

#[test]
fn bench_synth_writes_its_tables_files_and_images() {
    let exemplars = repo("assets/exemplars");
    assert!(
        exemplars.join("leather.pat").exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        exemplars.display()
    );
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "synth", "--exemplars", "leather", "--res", "64x64"])
            .args(["--energy-samples", "256", "--runs", "1", "--warmup", "0"])
            .args(["--quality-seeds", "2"])
            .arg("--exemplar-dir")
            .arg(&exemplars),
        out.path(),
        &[
            "leather 64x64 analysis",
            "leather 64x64 -> 64x64",
            "lazysolid gpu passes (timestamps)",
            "lazysolid end-to-end cold (wall)",
            "lazysolid end-to-end warm (wall)",
            "texture-synthesis 0.8.2 (2 threads)",
            "energy lazysolid",
            "mean of 2 seed(s)",
            "gpu profile",
            "target leather 64x64 -> 64x64: >= 20x faster",
        ],
    );
    // The analysis row and five rows of the one case.
    assert_eq!(bench.csv().1.len(), 1 + 5);
    let json = bench.json();
    let derived = &json["derived"];
    for key in [
        "leather 64x64 -> 64x64: lazysolid energy",
        "leather 64x64 -> 64x64: texture-synthesis energy",
        "leather 64x64 -> 64x64: lazysolid histogram distance",
        "leather 64x64 -> 64x64: texture-synthesis histogram distance",
        "leather 64x64 -> 64x64: lazysolid period repetition",
        "leather 64x64 -> 64x64: texture-synthesis period repetition",
    ] {
        let v = derived[key].as_f64().unwrap_or_else(|| panic!("no {key}"));
        assert!(v.is_finite() && v >= 0.0, "{key} = {v}");
    }
    // The mean lies within the range of the two seeds' energies, for both synthesizers.
    for who in ["lazysolid", "texture-synthesis"] {
        let get = |key: &str| {
            let key = format!("leather 64x64 -> 64x64: {who} {key}");
            derived[&key].as_f64().unwrap_or_else(|| panic!("no {key}"))
        };
        let (lo, mean, hi) = (get("energy min"), get("energy"), get("energy max"));
        assert!(lo <= mean && mean <= hi, "{who}: {lo} {mean} {hi}");
    }
    assert_eq!(derived["quality seeds"], 2.0);
    // 58² interior positions on the coarsest subgrid with at most 256: every 4th, 15².
    assert_eq!(derived["leather 64x64 -> 64x64: energy samples"], 225.0);
    let ratio = json["rows"][1]["ratio"].as_f64().expect("a ratio");
    assert!(ratio > 0.0, "{ratio}");
    let figures = bench.figures();
    let names = bench.figure_names();
    for f in [
        "leather-64-lazysolid-vs-texture-synthesis.png",
        "synth-times.png",
    ] {
        assert!(names.iter().any(|n| n == f), "missing {f} in {names:?}");
    }
    assert!(!names.iter().any(|n| n.contains("partial")), "{names:?}");
    let side = image::open(figures.join("leather-64-lazysolid-vs-texture-synthesis.png")).unwrap();
    assert_eq!((side.width(), side.height()), (2 * 64 + 8, 64));
}

#[test]
fn bench_synth_refuses_missing_exemplars_and_bad_sizes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--res", "4"]));
    assert!(
        !ok && err.contains("--res 4x4 is out of range (7..=2048 per side)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--res", "64x32"]));
    assert!(
        !ok && err.contains("--res 64x32") && err.contains("square"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--quality-seeds", "0"]));
    assert!(
        !ok && err.contains("--quality-seeds 0 is out of range (1..=16)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "synth",
        "--exemplars",
        "no-such-pattern",
        "--exemplar-dir",
        "/no/such/dir",
    ]));
    assert!(
        !ok && err.contains("/no/such/dir/no-such-pattern.pat") && err.contains("fetch-assets"),
        "{err}"
    );
}
