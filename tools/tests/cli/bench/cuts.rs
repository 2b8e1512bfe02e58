//! `lazysolid bench cuts`: every plane cut and the fracture timed, one row each.

use crate::support::{lazysolid, terra_square, BenchRun};

/// `lazysolid bench cuts` times every plane cut and the fracture as one row each, with the
/// voxels the caps need, the new ones synthesized, and the store's growth.
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
            "lazy request + insert (wall)",
            "thesis (2008 GPU): 8 ms",
        ],
    );
    assert!(bench.json()["rows"]
        .as_array()
        .is_some_and(|r| r.len() == 5));
}
