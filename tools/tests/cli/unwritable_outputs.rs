//! Outputs that cannot be written (a missing folder, a folder for a file, a folder below a file)
//! fail every subcommand within seconds, before any device is created or anything is written.

use crate::support::{lazysolid, repo};
use std::process::Command;

/// Runs `c` with `-v` (which announces the device as soon as one is created); it must fail
/// within seconds, before any device exists, with an error that names every one of `needles`.
fn fails_before_any_device(c: &mut Command, needles: &[&str]) {
    let start = std::time::Instant::now();
    let out = c
        .arg("-v")
        .env("LAZYSOLID_VALIDATION", "1")
        .output()
        .unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    for needle in needles {
        assert!(err.contains(needle), "missing {needle:?} in {err}");
    }
    assert!(!err.contains("device "), "a device was created: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(seconds < 10.0, "{seconds} s");
}

#[test]
fn unwritable_outputs_fail_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let scene = repo("scenes/test/interior.toml");
    let missing = dir.path().join("no-such-folder").join("out.png");
    let missing_text = missing.display().to_string();
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(&missing),
        &[&missing_text, "does not exist"],
    );
    // The EXR beside a writable PNG is checked too.
    let exr = dir.path().join("no-such-folder").join("out.exr");
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(dir.path().join("out.png"))
            .arg("--exr")
            .arg(&exr),
        &["--exr", &exr.display().to_string()],
    );
    // A folder is not a file.
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(dir.path()),
        &["is a folder"],
    );
    fails_before_any_device(
        lazysolid()
            .arg("synth")
            .arg("terra")
            .arg("-o")
            .arg(&missing),
        &[&missing_text],
    );
    // A results folder below a file.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "").unwrap();
    fails_before_any_device(
        lazysolid()
            .args(["bench", "prims", "--quick", "--out-dir"])
            .arg(file.join("results")),
        &["--out-dir", "a-file", "is not a folder"],
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "nothing written"
    );
}
