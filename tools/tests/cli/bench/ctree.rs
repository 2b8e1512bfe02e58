//! `lazysolid bench ctree`: rate–distortion of the compressed trees on every test image with
//! the codecs beside them, Table 4.2 where each first matches BC1, device builds equal to host
//! builds, lookups against the stores and a MIP texture; bad sizes refused.

use crate::support::{lazysolid, run, BenchRun};

#[test]
fn bench_ctree_writes_curves_tables_and_timings() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid().args([
            "bench",
            "ctree",
            "--quick",
            "--lookups",
            "65536",
            "--warmup",
            "0",
            "--runs",
            "1",
        ]),
        out.path(),
        &[
            "## terrain",
            "## distance",
            "## sky",
            "## photo",
            "| level | nodes | internal | scale | padding (bytes) |",
            "at 4 bpp against BC1",
            "gpu builder",
            "perfect hash (8 lookups)",
            "plain R8 MIP texture",
        ],
    );
    // The device builds were checked byte for byte against the host's inside the run: 2 grey
    // images and the volume, each built on both; 5 lookups in 3D, 2 in 2D.
    assert_eq!(bench.column("case").len(), 2 * 3 + 5 + 2);
    let dir = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("the run's figure folder");
    for name in [
        "rd-terrain.png",
        "rd-distance.png",
        "rd-sky.png",
        "rd-photo.png",
        "ctree-rd.csv",
        "ctree-rd.json",
        "ctree-tables.md",
    ] {
        assert!(
            dir.join(name).is_file(),
            "{name} missing in {}",
            dir.display()
        );
    }
    // Every image's topology where it first matches BC1 is within the 0.5 B/node.
    let json = bench.json();
    let notes = json["derived"].as_object().expect("derived values");
    let per_node: Vec<f64> = notes
        .iter()
        .filter(|(k, _)| k.ends_with("topology B/node there"))
        .map(|(_, v)| v.as_f64().unwrap())
        .collect();
    assert_eq!(per_node.len(), 4, "{notes:?}");
    assert!(
        per_node.iter().all(|&b| b > 0.0 && b <= 0.5),
        "{per_node:?}"
    );
}

#[test]
fn bench_ctree_refuses_a_volume_past_the_lattice() {
    let (ok, _, err) = run(lazysolid().args(["bench", "ctree", "--volume", "600"]));
    assert!(!ok);
    assert!(err.contains("--volume 600"), "{err}");
}
