//! The assets: meshes are found by name from any folder, `LAZYSOLID_ASSETS` first, and an unknown
//! name lists the known ones and where it looked.

use crate::support::{lazysolid, repo, run, BenchRun};

#[test]
fn meshes_are_found_by_name_from_any_folder() {
    let elsewhere = tempfile::tempdir().unwrap();
    let out = elsewhere.path().join("results");
    let bench = BenchRun::new(
        lazysolid()
            .current_dir(elsewhere.path())
            .args(["bench", "trace", "--mesh", "cube", "--res", "16x16"])
            .args(["--runs", "1", "--warmup", "0"]),
        &out,
        &["primary rays", "gpu cwbvh two-level"],
    );
    // The cube of the assets: its 12 triangles.
    let faces: f64 = std::fs::read_to_string(repo("assets/meshes/cube.off"))
        .unwrap()
        .lines()
        .nth(1)
        .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        .unwrap();
    assert_eq!(bench.json()["derived"]["triangles"], faces);

    // An unknown name lists the known ones and where it looked.
    let (ok, _, err) = run(lazysolid()
        .current_dir(elsewhere.path())
        .args(["bench", "trace", "--mesh", "dragon"]));
    assert!(
        !ok && err.contains("--mesh dragon: no mesh named \"dragon\"")
            && err.contains("armadillo")
            && err.contains("bunny00"),
        "{err}"
    );

    // LAZYSOLID_ASSETS comes first: a folder holding only `tiny` knows no cube.
    let assets = elsewhere.path().join("my-assets");
    std::fs::create_dir_all(assets.join("meshes")).unwrap();
    std::fs::copy(
        repo("assets/meshes/cube.off"),
        assets.join("meshes/tiny.off"),
    )
    .unwrap();
    let (ok, _, err) = run(lazysolid()
        .env("LAZYSOLID_ASSETS", &assets)
        .args(["bench", "trace", "--mesh", "cube"]));
    assert!(
        !ok && err.contains("known: tiny") && err.contains("my-assets"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid()
        .env("LAZYSOLID_ASSETS", elsewhere.path().join("nowhere"))
        .args(["bench", "trace", "--mesh", "cube"]));
    assert!(
        !ok && err.contains("LAZYSOLID_ASSETS=") && err.contains("nowhere"),
        "{err}"
    );
}
