//! `lazysolid bench psh`: the perfect spatial hash's construction and query table, files and
//! figures, the GPU construction matching the CPU reference.

use crate::support::{lazysolid, BenchRun};

#[test]
fn bench_psh_writes_its_table_files_and_figures() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "psh", "--quick", "--runs", "1", "--warmup", "0"])
            .args(["--builder", "gpu", "--mesh", "armadillo"]),
        out.path(),
        &[
            "random-2d build",
            "cpu reference (1 thread)",
            "gpu construction",
            "voxels-128 query",
            "coherent hash lf 0.85 (gpu)",
            "dense array (gpu)",
            "blocked R=64: chosen b",
        ],
    );
    let json = bench.json();
    // Each build row names its construction; the perfect hash's queries read the table of
    // --builder gpu; the other structures name none.
    for row in json["rows"].as_array().unwrap() {
        let expected = match row["implementation"].as_str().unwrap() {
            "cpu reference (1 thread)" => Some("cpu"),
            "gpu construction" | "perfect hash (gpu)" => Some("gpu"),
            _ => None,
        };
        assert_eq!(row["builder"].as_str(), expected, "{row}");
    }
    assert!(bench.column("builder").iter().any(|b| b == "gpu"));
    let derived = &json["derived"];
    // The GPU construction ends at the CPU reference's sizes on every dataset.
    for set in ["random-2d", "image", "voxels-128"] {
        let get = |k: &str| {
            derived[format!("{set}: {k}")]
                .as_f64()
                .unwrap_or_else(|| panic!("no {set}: {k}"))
        };
        assert_eq!(
            get("cpu |Phi| per axis"),
            get("gpu |Phi| per axis"),
            "{set}"
        );
        let bits = get("gpu Phi bits per key");
        assert!(bits > 0.0 && bits.is_finite(), "{set}: {bits}");
    }
    let figures = bench.figures();
    for f in [
        "psh-construction.png",
        "psh-queries.png",
        "psh-blocked-bytes.png",
    ] {
        assert!(figures.join(f).exists(), "missing {f}");
    }
}
