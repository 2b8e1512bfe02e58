//! `lazysolid synth`: 2D synthesis writes its texture and coordinate map with the analysis cache
//! and metrics, and names a bad exemplar without writing anything.

use crate::support::{lazysolid, repo, run};

#[test]
fn synth_writes_texture_and_coordinate_map_with_metrics() {
    let exemplar = repo("assets/exemplars/terra.pat");
    assert!(
        exemplar.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        exemplar.display()
    );
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let out = dir.path().join("terra.png");
    // The exemplar by its asset name, from a folder outside the repository.
    let synth = |extra: &[&str]| {
        let (ok, stdout, err) = run(lazysolid()
            .current_dir(dir.path())
            .arg("synth")
            .arg("terra")
            .args(["--res", "48x32", "--offset", "-70,5", "--seed", "4"])
            .args(["--energy-samples", "64"])
            .args(extra)
            .args(["-o", "terra.png"])
            .env("LAZYSOLID_CACHE_DIR", cache.path())
            .env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        assert!(stdout.contains("terra.pat"), "{stdout}");
        (stdout, std::fs::read(&out).unwrap())
    };
    // The first run analyses the exemplar and caches the analysis, the second reads it, and
    // both write the same image; --no-cache neither reads nor writes the cache.
    let (stdout, first) = synth(&[]);
    for needle in [
        "cache miss",
        "synthesis (GPU)",
        "neighbourhood energy",
        "colour histogram distance",
    ] {
        assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
    }
    let cached: Vec<_> = std::fs::read_dir(cache.path().join("synth-analysis"))
        .unwrap()
        .collect();
    assert_eq!(cached.len(), 1);
    let (stdout, second) = synth(&[]);
    assert!(stdout.contains("cache hit"), "{stdout}");
    assert_eq!(first, second);
    let (stdout, third) = synth(&["--no-cache"]);
    assert!(stdout.contains("cache off"), "{stdout}");
    assert_eq!(first, third);
    let image = image::open(&out).unwrap();
    assert_eq!((image.width(), image.height()), (48, 32));
    let coords = image::open(dir.path().join("terra.coords.png")).unwrap();
    assert_eq!((coords.width(), coords.height()), (48, 32));
    // Only the two PNGs: no temporary file is left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

/// `--relief-out`: the relief channel through the synthesized coordinates, a grey PNG of the
/// window's size whose codes vary (features low, far from them high); a path that is not a
/// PNG is refused before any work.
#[test]
fn synth_writes_the_relief_channel() {
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let synth = |relief: &str| {
        run(lazysolid()
            .current_dir(dir.path())
            .args(["synth", "cracked", "--res", "64x40", "--seed", "2"])
            .args([
                "--energy-samples",
                "64",
                "--relief-out",
                relief,
                "-o",
                "c.png",
            ])
            .env("LAZYSOLID_CACHE_DIR", cache.path())
            .env("LAZYSOLID_VALIDATION", "1"))
    };
    let (ok, stdout, err) = synth("c.relief.png");
    assert!(ok, "{err}");
    assert!(
        stdout.contains("relief channel: feature distance"),
        "{stdout}"
    );
    let relief = image::open(dir.path().join("c.relief.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(relief.dimensions(), (64, 40));
    assert!(relief.pixels().all(|p| p[0] == p[1] && p[1] == p[2]));
    let codes: std::collections::BTreeSet<u8> = relief.pixels().map(|p| p[0]).collect();
    assert!(codes.len() > 16, "{codes:?}");
    assert!(codes.iter().all(|&c| c >= 2), "{codes:?}");
    let (ok, _, err) = synth("c.relief.txt");
    assert!(!ok);
    assert!(
        err.contains("--relief-out c.relief.txt") && err.contains(".png"),
        "{err}"
    );
}

#[test]
fn synth_names_a_bad_exemplar_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = dir.path().join("tiny.png");
    image::RgbImage::new(8, 8).save(&tiny).unwrap();
    let out = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("synth").arg(&tiny).arg("-o").arg(&out));
    assert!(!ok);
    assert!(
        err.contains("tiny.png") && err.contains("8x8") && err.contains("at least 16"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists());
    // An empty cache folder variable is refused by name, before any work.
    let terra = repo("assets/exemplars/terra.pat");
    let (ok, _, err) = run(lazysolid()
        .arg("synth")
        .arg(&terra)
        .arg("-o")
        .arg(&out)
        .env("LAZYSOLID_CACHE_DIR", ""));
    assert!(!ok && err.contains("LAZYSOLID_CACHE_DIR"), "{err}");
    assert!(!out.exists());
}
