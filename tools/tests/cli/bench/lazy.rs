//! `lazysolid bench lazy`: lazy synthesis of a mesh's voxels, each store's bytes and the
//! cross-section figure.

use crate::support::{fnv1a, lazysolid, terra_square, BenchRun};

/// `bench lazy` on the bunny at 16³ with a 16² terra crop (its candidates take seconds): the
/// timed row, the per-level notes, each store's bytes and the cross-section figure at the
/// resolution `--section-res` asks for; and the correction's profile, part by part.
#[test]
fn bench_lazy_writes_voxels_stores_and_a_cross_section() {
    let out = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "lazy", "--meshes", "bunny00", "--voxel-res", "16"])
            .arg("--exemplar")
            .arg(&exemplar)
            .args(["--runs", "1", "--warmup", "0", "--section-res", "32"])
            .arg("--profile-correction")
            .env("LAZYSOLID_CACHE_DIR", dir.path().join("cache")),
        out.path(),
        &[
            "bunny00 16³",
            "gpu lazy (wall)",
            "bunny00 16³: finest-level voxels synthesized % of R³",
            "bunny00 16³: store MB: tiletree",
            "bunny00 16³: store MB: perfect hash (trilinear)",
            "bunny00 16³: level 0 voxels",
            "bunny00 32³ cross-section z = 16: voxel versions computed after the surface",
            "bunny00 16³: host waits (submissions)",
            "bunny00 16³: last run device ms, every submission",
            "bunny00 16³, correction profile (fresh state, keep): neighbourhood sums adds ms",
            "bunny00 16³, correction profile (fresh state, keep): kernel synth/solid/lazy_correct.comp dispatches",
        ],
    );
    // The profile times the correction once per cumulative part: each run computes at least
    // what the one before it did, and the whole correction is the synthesizer's work.
    let json = bench.json();
    let note = |k: &str| {
        json["derived"][k]
            .as_f64()
            .unwrap_or_else(|| panic!("{k}: {}", json["derived"]))
    };
    let profile = "bunny00 16³, correction profile (fresh state, keep)";
    let parts = [
        "neighbour lookups and reads",
        "neighbourhood sums",
        "candidate sets and own-role distances",
        "candidate distances and choice",
    ]
    .map(|p| note(&format!("{profile}: up to {p}: lazy_correct device ms")));
    assert!(parts.iter().all(|&ms| ms > 0.0), "{parts:?}");
    // The same request with the voxels visited in key order: the same triples (checked by
    // the bench, which fails otherwise), its own device time.
    assert!(
        note(&format!(
            "{profile}: voxels in key order: lazy_correct device ms"
        )) > 0.0
    );
    assert!(
        note(&format!(
            "{profile}: key order / grouped, lazy_correct device time"
        )) > 0.0
    );
    assert!(
        note(&format!("{profile}: voxel versions computed"))
            == note("bunny00 16³: voxel versions computed"),
        "the profiled request is the measured one"
    );
    let figures = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder");
    let section = image::open(figures.join("bunny00-32-section-z16.png")).unwrap();
    assert_eq!((section.width(), section.height()), (32, 32));
    // Byte for byte the figure drawn before the solid recipe made the suite's lazy states
    // (10d48bd).
    let bytes = std::fs::read(figures.join("bunny00-32-section-z16.png")).unwrap();
    assert_eq!(fnv1a(&bytes), 0xfedb_450e_fffb_c4d9);
    // And the same work: the voxels synthesized per level and in all (non-timing columns of
    // the run before the recipe, 10d48bd).
    for (key, want) in [
        ("bunny00 16³: level 0 voxels synthesized", 9073.0),
        ("bunny00 16³: level 1 voxels synthesized", 8519.0),
        ("bunny00 16³: level 2 voxels synthesized", 7739.0),
        ("bunny00 16³: level 3 voxels synthesized", 6293.0),
        ("bunny00 16³: level 4 voxels synthesized", 1530.0),
        ("bunny00 16³: voxel versions computed", 63894.0),
        (
            "bunny00 16³: voxels in the dependency sets, all levels",
            37207.0,
        ),
        (
            "bunny00 32³ cross-section z = 16: voxel versions computed after the surface",
            704.0,
        ),
    ] {
        assert_eq!(json["derived"][key].as_f64(), Some(want), "{key}");
    }
    assert!(bench.json()["rows"]
        .as_array()
        .is_some_and(|r| r.len() == 1));
}
