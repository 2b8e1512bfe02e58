//! `lazysolid bench hash`: the spatial hashes' tables, files and figures, and bad load factors,
//! datasets, schemes, sizes and meshes refused.

use crate::support::{lazysolid, repo, run, BenchRun};

#[test]
fn bench_hash_writes_tables_files_and_figures() {
    let mesh = repo("assets/meshes/armadillo.off");
    assert!(
        mesh.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        mesh.display()
    );
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "hash",
                "--image-res",
                "256x256",
                "--voxel-res",
                "32",
                "--random-keys",
                "4096",
                "--random-universe",
                "512",
            ])
            .args([
                "--load-factors",
                "0.5,0.85,0.99",
                "--runs",
                "1",
                "--warmup",
                "0",
                "--mesh",
            ])
            .arg(&mesh),
        out.path(),
        &[
            "image lf 0.85 query sorted 100%",
            "dense array (gpu)",
            "hashbrown (cpu, 2 threads)",
            "target: image lf 0.85 sorted queries coherent / random",
        ],
    );
    // A name with commas ("hashbrown (cpu, 2 threads)") is one quoted field: every record has
    // the header's length (checked by csv()) and the name reads back whole.
    let implementations = bench.column("implementation");
    assert!(
        implementations
            .iter()
            .any(|i| i == "hashbrown (cpu, 2 threads)"),
        "{implementations:?}"
    );
    assert!(bench
        .column("ratio")
        .iter()
        .any(|r| r.parse::<f64>().is_ok()));
    bench.file("json");
    let names = bench.figure_names();
    for f in [
        "age-histogram.png",
        "image-insert-vs-load-factor.png",
        "voxels-query-vs-load-factor.png",
        "table-contents-coherent-lf0.99.png",
        "max-age-map-random-lf0.85.png",
    ] {
        assert!(names.iter().any(|n| n == f), "missing {f} in {names:?}");
    }
    assert!(!names.iter().any(|n| n.contains("partial")), "{names:?}");
}

#[test]
fn bench_hash_refuses_bad_load_factors_and_missing_meshes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--load-factors", "0.5,1.5"]));
    assert!(
        !ok && err.contains("--load-factors must lie in (0, 1]"),
        "{err}"
    );
    let (ok, _, err) =
        run(lazysolid().args(["bench", "hash", "--quick", "--mesh", "/no/such/mesh.off"]));
    assert!(
        !ok && err.contains("/no/such/mesh.off") && err.contains("fetch-assets"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--datasets", "image,fish"]));
    assert!(
        !ok && err.contains("'fish'")
            && err.contains("--datasets")
            && err.contains("[possible values: random-2d, image, voxels]"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--schemes", "linear"]));
    assert!(
        !ok && err.contains("'linear'")
            && err.contains("[possible values: coherent, random, cuckoo]"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--image-res", "256x128"]));
    assert!(
        !ok && err.contains("--image-res 256x128") && err.contains("square"),
        "{err}"
    );
}
