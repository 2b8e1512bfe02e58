//! Flags renamed across the subcommands: each old spelling is refused with its new one named.

use crate::support::lazysolid;

#[test]
fn renamed_flags_are_refused_by_name() {
    for (args, old, new) in [
        (
            &["bench", "textures", "--view", "64"][..],
            "--view",
            "--res",
        ),
        (
            &["bench", "hash", "--voxel-resolution", "32"],
            "--voxel-resolution",
            "--voxel-res",
        ),
        (
            &["bench", "hash", "--image-size", "256"],
            "--image-size",
            "--image-res",
        ),
        (
            &["bench", "psh", "--voxel-resolutions", "64"],
            "--voxel-resolutions",
            "--voxel-res",
        ),
        (
            &["bench", "psh", "--blocked-resolution", "64"],
            "--blocked-resolution",
            "--blocked-voxel-res",
        ),
        (&["bench", "synth", "--sizes", "64"], "--sizes", "--res"),
        (
            &["bench", "solid", "--builders", "host"],
            "--builders",
            "--candidates",
        ),
        (
            &["bench", "prims", "--out", "results"],
            "--out",
            "--out-dir",
        ),
        (
            &["synth", "terra", "-o", "x.png", "--size", "64"],
            "--size",
            "--res",
        ),
        (
            &["solid", "terra", "-o", "x.nrrd", "--size", "64"],
            "--size",
            "--voxel-res",
        ),
        (
            &["bench", "solid", "--sizes", "64"],
            "--sizes",
            "--voxel-res",
        ),
        (&["multiscale", "g.toml", "--size", "64"], "--size", "--res"),
        (
            &["zoom", "g.toml", "--frames", "3"],
            "--frames",
            "--frame-count",
        ),
        (&["zoom", "g.toml", "-o", "frames"], "-o", "--out-dir"),
        (
            &["fracture", "cube", "--pieces", "2", "-o", "pieces"],
            "-o",
            "--out-dir",
        ),
        (
            &["bench", "multiscale", "--quality-size", "64"],
            "--quality-size",
            "--quality-res",
        ),
    ] {
        let out = lazysolid().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(&format!("unexpected argument '{old}'"))
                && err.contains(&format!("`{old}` is now `{new}`")),
            "{args:?}: {err}"
        );
    }
}
