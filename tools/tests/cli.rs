//! The `lazysolid` binary as a user runs it, including the ways it must fail clearly.

use std::process::Command;

fn lazysolid() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lazysolid"));
    c.env_remove("LAZYSOLID_DEVICE")
        .env_remove("LAZYSOLID_VALIDATION");
    c
}

fn run(c: &mut Command) -> (bool, String, String) {
    let out = c.output().expect("lazysolid runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn device_lists_limits_and_marks_the_chosen_device() {
    let (ok, out, err) = run(lazysolid().arg("device"));
    assert!(ok, "{err}");
    for needle in [
        "maxStorageBufferRange",
        "device heap",
        "subgroup size",
        "64-bit buffer atomics",
        "timestamps",
        "<- used by lazysolid",
    ] {
        assert!(out.contains(needle), "missing {needle:?} in:\n{out}");
    }
}

#[test]
fn no_vulkan_device_is_a_clear_error() {
    let (ok, _, err) = run(lazysolid()
        .arg("device")
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json"));
    assert!(!ok);
    assert!(
        err.contains("no Vulkan device found") && err.contains("mesa-vulkan-drivers"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn missing_validation_layer_is_a_clear_error() {
    let empty = tempfile::tempdir().unwrap();
    let (ok, _, err) = run(lazysolid()
        .args(["bench", "prims", "--quick", "--runs", "1", "--warmup", "0"])
        .env("LAZYSOLID_VALIDATION", "1")
        .env("VK_LAYER_PATH", empty.path())
        .env("VK_ADD_LAYER_PATH", empty.path()));
    assert!(!ok);
    assert!(
        err.contains("VK_LAYER_KHRONOS_validation is not installed")
            && err.contains("vulkan-validationlayers"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn unknown_device_lists_the_available_ones() {
    let (ok, _, err) =
        run(lazysolid().args(["--device", "no-such-gpu", "bench", "prims", "--quick"]));
    assert!(!ok);
    assert!(
        err.contains("no-such-gpu") && err.contains("available devices: 0: "),
        "{err}"
    );
}

#[test]
fn bench_prims_writes_its_table_and_files() {
    let out = tempfile::tempdir().unwrap();
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "bench",
            "prims",
            "--scan-elements",
            "20000",
            "--sort-elements",
            "5000",
            "--runs",
            "2",
            "--warmup",
            "1",
            "--out",
        ])
        .arg(out.path())
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    assert!(
        stdout.contains("sort u32 keys") && stdout.contains("ratio"),
        "{stdout}"
    );
    let files: Vec<_> = std::fs::read_dir(out.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let csv = files
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "csv"))
        .expect("a CSV file");
    let json = files
        .iter()
        .find(|p| p.extension().is_some_and(|e| e == "json"))
        .expect("a JSON file");
    assert_eq!(files.len(), 2, "no partial files left: {files:?}");
    let csv = std::fs::read_to_string(csv).unwrap();
    assert!(
        csv.starts_with("# {")
            && csv.contains("\"device\"")
            && csv.contains("\"git_revision\"")
            && csv.contains("\"date_utc\""),
        "{csv}"
    );
    assert_eq!(
        csv.lines().filter(|l| !l.starts_with('#')).count(),
        1 + 14,
        "header + 14 rows:\n{csv}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
    assert!(json["run"]["driver"]
        .as_str()
        .is_some_and(|d| !d.is_empty()));
    assert_eq!(json["rows"].as_array().unwrap().len(), 14);
    assert!(
        json["rows"][0]["stats"]["samples_ms"]
            .as_array()
            .unwrap()
            .len()
            == 2
    );
}

#[test]
fn bad_arguments_are_refused() {
    let (ok, _, err) = run(lazysolid().args(["bench", "prims", "--runs", "0"]));
    assert!(!ok && err.contains("--runs must be at least 1"), "{err}");
    let (ok, _, err) = run(lazysolid().args(["bench", "prims", "--scan-elements", "lots"]));
    assert!(!ok && err.contains("invalid value"), "{err}");
}

#[test]
fn bench_hash_writes_tables_files_and_figures() {
    let mesh =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/meshes/armadillo.off");
    assert!(
        mesh.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        mesh.display()
    );
    let out = tempfile::tempdir().unwrap();
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "bench",
            "hash",
            "--image-size",
            "256",
            "--voxel-resolution",
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
        .arg(&mesh)
        .arg("--out")
        .arg(out.path())
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    for needle in [
        "image lf 0.85 query sorted 100%",
        "dense array (gpu)",
        "hashbrown (cpu, 2 threads)",
        "target: image lf 0.85 sorted queries coherent / random",
    ] {
        assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
    }
    let entries: Vec<_> = std::fs::read_dir(out.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(entries
        .iter()
        .any(|p| p.extension().is_some_and(|e| e == "csv")));
    assert!(entries
        .iter()
        .any(|p| p.extension().is_some_and(|e| e == "json")));
    let figures = entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder");
    let names: Vec<String> = std::fs::read_dir(figures)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
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
}
