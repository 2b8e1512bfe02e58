//! Damaged files through every subcommand that reads them: a real file cut short or with
//! flipped bytes ends in exit status 1 with a message that names the file, never a panic, and
//! leaves the output folder as it was (no output, no temporary file). The readers themselves
//! are fuzzed in `tests/tests/fuzz/`; this checks what the commands do with their errors.

use crate::support::{lazysolid, repo};
use std::path::{Path, PathBuf};
use std::process::Command;

/// `file`'s bytes cut to `keep` of them (a fraction) with every `stride`-th byte after the
/// header inverted: how a download or a disk damages a file.
fn damaged(file: &Path, keep: f64, stride: usize) -> Vec<u8> {
    let mut bytes = std::fs::read(file).unwrap();
    bytes.truncate((bytes.len() as f64 * keep) as usize);
    for b in bytes.iter_mut().skip(16).step_by(stride) {
        *b = !*b;
    }
    bytes
}

/// Writes `bytes` as `name` in `dir`.
fn put(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// Runs `c` writing into the empty folder `out`; it must fail with status 1 naming `name`,
/// and `out` must still be empty.
fn refused(c: &mut Command, out: &Path, name: &str) {
    let output = c.env("LAZYSOLID_VALIDATION", "1").output().unwrap();
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{name}: {err}");
    assert!(err.contains(name), "the error does not name {name}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    let left: Vec<_> = std::fs::read_dir(out).unwrap().collect();
    assert!(
        left.is_empty(),
        "{name}: {left:?} left in the output folder"
    );
}

/// The scene `name` of one mesh (its lines `mesh`) and one material (`material`).
fn scene(dir: &Path, name: &str, mesh: &str, material: &str) -> PathBuf {
    let text = format!(
        "[camera]\nposition = [2.0, 2.0, 2.0]\nlook_at = [0.5, 0.5, 0.5]\nfov_y = 40\n\
         [render]\nwidth = 16\nheight = 16\nspp = 1\n\
         [[mesh]]\nname = \"m\"\n{mesh}\n\
         [[material]]\nname = \"a\"\n{material}\n\
         [[instance]]\nmesh = \"m\"\nmaterial = \"a\"\n"
    );
    put(dir, name, text.as_bytes())
}

#[test]
fn damaged_files_are_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();
    let walnut = put(
        d,
        "walnut.pat",
        &damaged(&repo("assets/exemplars/walnut.pat"), 0.6, 97),
    );
    let bumps = put(
        d,
        "bumps.png",
        &damaged(&repo("scenes/normal-maps/bumps.png"), 0.8, 211),
    );
    let cow = put(
        d,
        "cow.off",
        &damaged(&repo("assets/meshes/cow.off"), 0.5, 389),
    );

    refused(
        lazysolid()
            .arg("synth")
            .arg(&walnut)
            .arg("-o")
            .arg(out.join("s.png")),
        &out,
        "walnut.pat",
    );
    refused(
        lazysolid()
            .arg("synth")
            .arg(&bumps)
            .arg("-o")
            .arg(out.join("s.png")),
        &out,
        "bumps.png",
    );
    refused(
        lazysolid()
            .arg("solid")
            .arg(&walnut)
            .args(["--voxel-res", "64", "-o"])
            .arg(out.join("v.nrrd")),
        &out,
        "walnut.pat",
    );
    refused(
        lazysolid()
            .args(["fracture"])
            .arg(&cow)
            .args(["--pieces", "4", "--out-dir"])
            .arg(&out),
        &out,
        "cow.off",
    );

    // The scene's own files: a mesh, a height map and a volume, each damaged.
    let volume = put(
        d,
        "volume.nrrd",
        b"NRRD0004\ntype: uint8\ndimension: 4\nsizes: 3 4 4 4\nencoding: raw\n\n\x01\x02",
    );
    let cases = [
        (
            scene(
                d,
                "mesh.toml",
                "path = \"cow.off\"",
                "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]",
            ),
            "cow.off",
        ),
        (
            scene(
                d,
                "map.toml",
                "shape = \"quad\"",
                "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\nheight_map = \"bumps.png\"",
            ),
            "bumps.png",
        ),
        (
            scene(
                d,
                "volume.toml",
                "shape = \"cube\"",
                "kind = \"lambertian\"\ntexture = { kind = \"volume\", path = \"volume.nrrd\", \
                 store = \"octree\", resolution = 16 }",
            ),
            "volume.nrrd",
        ),
    ];
    for (scene, name) in cases {
        refused(
            lazysolid()
                .arg("render")
                .arg(&scene)
                .arg("-o")
                .arg(out.join("r.png")),
            &out,
            name,
        );
    }
    // A scene cut short in the middle of a table.
    let whole = std::fs::read(repo("scenes/test/interior.toml")).unwrap();
    let cut = put(d, "cut.toml", &whole[..whole.len() / 3]);
    refused(
        lazysolid()
            .arg("render")
            .arg(&cut)
            .arg("-o")
            .arg(out.join("r.png")),
        &out,
        "cut.toml",
    );
    assert!(volume.exists());
}
