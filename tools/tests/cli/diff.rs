//! `lazysolid diff`: the FLIP statistics and error map of two images, the exit status of
//! `--max-mean`, and bad paths named.

use crate::support::{lazysolid, run};

/// Two 40x30 PNGs in a fresh folder: a gradient, and the same with a few pixels changed.
fn diff_pair() -> (tempfile::TempDir, std::path::PathBuf, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let reference = image::RgbImage::from_fn(40, 30, |x, y| {
        image::Rgb([(x * 6) as u8, (y * 8) as u8, ((x + y) * 3) as u8])
    });
    let mut test = reference.clone();
    for (x, y) in [(3, 4), (20, 15), (35, 27)] {
        test.put_pixel(x, y, image::Rgb([255, 255, 255]));
    }
    let (r, t) = (dir.path().join("ref.png"), dir.path().join("test.png"));
    reference.save(&r).unwrap();
    test.save(&t).unwrap();
    (dir, r, t)
}

/// The value printed on the `FLIP <name>` line.
fn flip_stat(stdout: &str, name: &str) -> f32 {
    stdout
        .lines()
        .find_map(|l| l.strip_prefix("FLIP ")?.strip_prefix(name))
        .unwrap_or_else(|| panic!("no FLIP {name} line in:\n{stdout}"))
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn diff_prints_statistics_and_writes_the_error_map() {
    let (dir, r, t) = diff_pair();
    let map = dir.path().join("error.png");
    let (ok, out, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .arg("--error-map")
        .arg(&map));
    assert!(ok, "{err}");
    assert!(out.contains("size        40x30 (1200 pixels)"), "{out}");
    let stats: Vec<f32> = ["mean", "median", "p95", "p99", "max"]
        .iter()
        .map(|n| flip_stat(&out, n))
        .collect();
    assert!(stats[0] > 0.0 && stats[0] < 0.05, "{out}");
    assert!(stats[1..].windows(2).all(|w| w[0] <= w[1]), "{out}");
    assert!(stats[4] > 0.3, "{out}");
    let written = image::open(&map).unwrap();
    assert_eq!((written.width(), written.height()), (40, 30));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);

    // The same image against itself: zero everywhere.
    let (ok, out, err) = run(lazysolid().arg("diff").arg(&r).arg(&r));
    assert!(ok, "{err}");
    assert_eq!(flip_stat(&out, "mean"), 0.0);
    assert_eq!(flip_stat(&out, "max"), 0.0);
}

#[test]
fn diff_max_mean_sets_the_exit_status() {
    let (_dir, r, t) = diff_pair();
    let (ok, out, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "0.5"]));
    assert!(ok, "{err}");
    assert!(out.contains("is within --max-mean 0.5"), "{out}");

    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "0.0001"])
        .output()
        .unwrap();
    // Its own status: 3, apart from errors (1) and validation errors (2).
    assert_eq!(out.status.code(), Some(3));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("is above --max-mean 0.0001") && err.contains("test.png"),
        "{err}"
    );
    // The statistics are still printed before the verdict.
    assert!(String::from_utf8_lossy(&out.stdout).contains("FLIP mean"));

    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "-1"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("outside 0..1"), "{err}");
    assert_eq!(out.status.code(), Some(1), "a bad argument is an error");
    // A missing image is an error too, not a failed comparison.
    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(r.with_file_name("nowhere.png"))
        .args(["--max-mean", "0.5"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    // `--help` documents the statuses.
    let (ok, help, _) = run(lazysolid().arg("--help"));
    assert!(ok && help.contains("Exit status:") && help.contains("3 `diff --max-mean`"));
}

#[test]
fn diff_bad_paths_are_named() {
    let (dir, r, _t) = diff_pair();
    let missing = dir.path().join("nowhere.png");
    let (ok, out, err) = run(lazysolid().arg("diff").arg(&r).arg(&missing));
    assert!(!ok && out.is_empty());
    assert!(
        err.contains("nowhere.png") && err.contains("cannot open") && !err.contains("panicked"),
        "{err}"
    );

    let small = dir.path().join("small.png");
    image::RgbImage::new(20, 30).save(&small).unwrap();
    let (ok, _, err) = run(lazysolid().arg("diff").arg(&r).arg(&small));
    assert!(
        !ok && err.contains("40x30") && err.contains("20x30") && err.contains("small.png"),
        "{err}"
    );

    let map = dir.path().join("missing-folder").join("map.png");
    let (ok, _, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&r)
        .arg("--error-map")
        .arg(&map));
    assert!(
        !ok && err.contains("error map") && err.contains("missing-folder"),
        "{err}"
    );
}
