//! `lazysolid bench glints`: the glint range-query structures, their memory against the explicit
//! method and the material's render time, and bad sizes and scenes refused.

use crate::support::{lazysolid, repo, run, BenchRun};

/// `lazysolid bench glints`: per example size, build rows of the sparse table and the min–max
/// mip (CPU and device) and query rows of all three methods (the suite fails unless their
/// answers are identical), the memory table beside the paper's 0.44 %, the material's render
/// rows (pruned, explicit, conductor), and bad sizes and scenes refused.
#[test]
fn bench_glints_measures_range_queries_memory_and_render_time() {
    let out = tempfile::tempdir().unwrap();
    let scene = repo("scenes/glints.toml");
    let bench = BenchRun::new(
        lazysolid().args([
            "bench",
            "glints",
            "--scene",
            scene.to_str().unwrap(),
            "--render-res",
            "32x24",
            "--spp",
            "1",
            "--res",
            "32,128",
            "--exemplar",
            "leather",
            "--queries",
            "500",
            "--coverage",
            "5120",
            "--warmup",
            "0",
            "--runs",
            "1",
        ]),
        out.path(),
        &[
            "32² leather query",
            "128² generated query",
            "sparse table (gpu)",
            "min–max mip (cpu, 1 thread)",
            "brute force (gpu)",
            "Mquery/s",
            "5120²",
            "0.44 % Chair",
            "render glints.toml 32×24 1 spp",
            "glint (pruned)",
            "glint (explicit)",
            "against the explicit reference",
        ],
    );
    let json = bench.json();
    assert_eq!(json["rows"].as_array().map(Vec::len), Some(23));
    assert!(
        json["derived"]["render glints.toml 32×24 1 spp: pruned / conductor"]
            .as_f64()
            .is_some_and(|r| r > 1.0)
    );
    // 32²: levels 0..=3 (l = 8) of 32² entries, 8 bytes each.
    assert_eq!(
        json["derived"]["32² leather: sparse table bytes"].as_f64(),
        Some((4 * 32 * 32 * 8) as f64)
    );
    assert!(
        json["derived"]["128² generated against coverage 5120²: constant / explicit %"]
            .as_f64()
            .is_some_and(|r| r > 0.0 && r < 1.0)
    );
    for (res, needle) in [
        ("48", "power of two"),
        ("32x64", "square"),
        ("8", "16..=2048"),
    ] {
        let (ok, _, err) = run(lazysolid().args(["bench", "glints", "--res", res]));
        assert!(!ok && err.contains(needle), "--res {res}: {err}");
    }
    let plain = repo("scenes/default.toml");
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "glints",
        "--part",
        "render",
        "--scene",
        plain.to_str().unwrap(),
    ]));
    assert!(
        !ok && err.contains("default.toml") && err.contains("no kind = \"glint\" material"),
        "{err}"
    );
}
