//! `lazysolid device` and the device every command runs on: the limits listed, the memory
//! switch, and the clear errors when no Vulkan device, no validation layer or no device of the
//! asked name is found.

use crate::support::{lazysolid, run};

#[test]
fn device_lists_limits_and_marks_the_chosen_device() {
    let (ok, out, err) = run(lazysolid().arg("device"));
    assert!(ok, "{err}");
    for needle in [
        "maxStorageBufferRange",
        "device heap",
        "subgroup size",
        "shaderBufferInt64Atomics",
        "timestamp queries on a compute queue",
        "<- used by lazysolid",
    ] {
        assert!(out.contains(needle), "missing {needle:?} in:\n{out}");
    }
}

#[test]
fn the_memory_switch_is_reported_and_an_unknown_value_is_an_error() {
    let (ok, out, err) = run(lazysolid()
        .arg("device")
        .env("LAZYSOLID_MEMORY", "device-local"));
    assert!(ok, "{err}");
    assert!(out.contains("memory mode: device-local"), "{out}");
    assert!(out.contains("timestamp valid bits"), "{out}");
    let (ok, _, err) = run(lazysolid()
        .arg("device")
        .env("LAZYSOLID_MEMORY", "discrete"));
    assert!(!ok);
    assert!(
        err.contains("LAZYSOLID_MEMORY")
            && err.contains("discrete")
            && err.contains("device-local"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
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
    // --validation asks for the layer as LAZYSOLID_VALIDATION=1 does.
    let (ok, _, err) = run(lazysolid()
        .args(["--validation", "bench", "prims", "--quick"])
        .env("VK_LAYER_PATH", empty.path())
        .env("VK_ADD_LAYER_PATH", empty.path()));
    assert!(
        !ok && err.contains("VK_LAYER_KHRONOS_validation is not installed")
            && err.contains("--validation is given"),
        "{err}"
    );
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
