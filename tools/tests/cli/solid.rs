//! `lazysolid solid`: solid synthesis writes the volume, its slices, slab and render with the
//! candidate cache and metrics, and names each bad input without writing anything.

use crate::support::{fnv1a, lazysolid, run, terra_square};

#[test]
fn solid_writes_volume_slices_and_slab_with_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("terra.nrrd");
    let cache = dir.path().join("cache");
    let solid = |extra: &[&str]| {
        run(lazysolid()
            .arg("solid")
            .args(extra)
            .arg(&exemplar)
            // One correction pass (the defaults' cost a few times more on lavapipe); the
            // synthesizer itself is tested in tests/tests/solid.rs.
            .args([
                "--voxel-res",
                "64",
                "--offset",
                "-70,5,9",
                "--seed",
                "4",
                "--passes",
                "1",
            ])
            .args(["--energy-samples", "64", "-o"])
            .arg(&out)
            .env("LAZYSOLID_CACHE_DIR", &cache)
            .env("LAZYSOLID_VALIDATION", "1"))
    };
    let (ok, stdout, err) = solid(&[]);
    assert!(ok, "{err}");
    for needle in [
        // On lavapipe (a CPU device) the candidates are computed on the host.
        "candidates (host)",
        "synthesis (GPU)",
        "peak GPU memory",
        "triples: 100.0 % are candidates of their pixel",
        "slice perpendicular to z vs E_z: SWD",
        "blockiness",
        "period repetition",
        "; over 8 slices SWD ratio ",
        "; per band fine / mid / coarse ",
        ", band contrast ",
        "energy",
        "gradient anisotropy (u - v)/(u + v): exemplars ",
        "every volume has x - y + z = 0",
        "orientation: diagonal correlation ",
        "diagonal correlation J_uv / sqrt(J_uu J_vv): exemplars ",
        "render (GPU)",
        "feature channel of ",
        "% of the pixels, distance clamped at 4 px, deviation ",
    ] {
        assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
    }
    let nrrd = std::fs::read(&out).unwrap();
    let header_end = nrrd.windows(2).position(|w| w == b"\n\n").unwrap() + 2;
    assert!(nrrd.starts_with(b"NRRD0004\n"));
    assert_eq!(nrrd.len() - header_end, 64 * 64 * 64 * 3);
    // Byte for byte what the command wrote before the solid recipe replaced its own pipeline
    // (10d48bd): the volume and every picture but the render, whose floats are compared by
    // FLIP elsewhere. A deliberate change of the synthesis updates these digests.
    assert_eq!(fnv1a(&nrrd[header_end..]), 0x4d1c_991d_c9b3_6c82, "volume");
    for (name, digest) in [
        ("x", 0x81f1_8823_9256_d0b5_u64),
        ("y", 0x88a7_b25b_c865_b0da),
        ("z", 0xc60c_7799_fe31_59a2),
        ("oblique", 0x750d_7a78_fd60_5783),
        ("slab", 0xc872_ba8f_4d19_4642),
        ("features", 0x641e_4359_3163_8d04),
    ] {
        let bytes = std::fs::read(out_dir.join(format!("terra.{name}.png"))).unwrap();
        assert_eq!(fnv1a(&bytes), digest, "terra.{name}.png");
    }
    for (name, width) in [
        ("x", 64),
        ("y", 64),
        ("z", 64),
        ("oblique", 64),
        ("slab", 9 * 16 + 8 * 2),
        ("render", 400),
        // Exemplar | mask | distance.
        ("features", 3 * 16 + 2 * 4),
    ] {
        let image = image::open(out_dir.join(format!("terra.{name}.png"))).unwrap();
        assert_eq!(image.width(), width, "{name}");
    }
    // The carved render's scene names the volume beside it and loads.
    let scene = out_dir.join("terra.scene.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains("path = \"terra.nrrd\""), "{text}");
    lazysolid_renderer::scene::Scene::load(&scene).unwrap();
    // The volume, seven pictures and the scene; no temporary file is left behind.
    assert_eq!(std::fs::read_dir(&out_dir).unwrap().count(), 9);
    assert!(stdout.contains("cache miss"), "{stdout}");
    // A second run reads the candidates back and writes the same volume.
    let (ok, stdout, err) = solid(&["--no-render"]);
    assert!(ok, "{err}");
    assert!(stdout.contains("cache hit"), "{stdout}");
    assert_eq!(std::fs::read(&out).unwrap(), nrrd);
}

#[test]
fn solid_names_each_bad_input_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let good = terra_square(dir.path(), 16);
    // Any image from 16 pixels a side up is fitted (tools/tests/cli/photos.rs); what is left
    // to refuse: smaller images, images past the decode limit, a crop that does not fit, an
    // exemplar side that is no power of two in 16..=256.
    let tiny = dir.path().join("tiny.png");
    image::RgbImage::new(8, 8).save(&tiny).unwrap();
    let huge = dir.path().join("huge.png");
    image::RgbImage::new(9000, 16).save(&huge).unwrap();
    let corrupt = dir.path().join("corrupt.png");
    std::fs::write(&corrupt, b"not a PNG at all").unwrap();
    let out = dir.path().join("out.nrrd");
    let path = |p: &std::path::Path| p.to_str().unwrap().to_owned();
    let cases: [(Vec<String>, &[&str]); 16] = [
        (
            vec!["--ey".into(), path(&tiny)],
            &["tiny.png", "8x8", "at least 16"],
        ),
        (
            vec!["--ex".into(), path(&huge)],
            &["huge.png", "9000x16", "8192"],
        ),
        (
            vec![
                "--fit".into(),
                "crop".into(),
                "--exemplar-side".into(),
                "32".into(),
            ],
            &["terra16.png", "--fit crop", "32x32"],
        ),
        (
            vec!["--exemplar-side".into(), "24".into()],
            &["--exemplar-side 24", "power of two"],
        ),
        (
            vec!["--exemplar-side".into(), "512".into()],
            &["--exemplar-side 512", "16..=256"],
        ),
        (
            vec!["--fit".into(), "stretch".into()],
            &["'stretch'", "auto, crop, resample"],
        ),
        (
            vec!["--ez".into(), "/nonexistent/e.png".into()],
            &["/nonexistent/e.png", "cannot read"],
        ),
        (
            vec!["--ey".into(), path(&corrupt)],
            &["corrupt.png", "cannot decode"],
        ),
        (
            vec!["--voxel-res".into(), "100".into()],
            &["--voxel-res 100", "64, 128, 256"],
        ),
        (
            vec!["--voxel-res".into(), "512".into()],
            &["--voxel-res 512", "64, 128, 256"],
        ),
        (
            vec!["--offset".into(), "300000000,0,0".into()],
            &["--offset 300000000,0,0", "268435456"],
        ),
        (vec!["--strip".into(), "4".into()], &["strip", "odd"]),
        (vec!["--s".into(), "80".into()], &["`s`", "1..=65"]),
        (
            vec!["--balance".into(), "65".into()],
            &["`balance`", "0..=64"],
        ),
        (
            vec!["--balance-levels".into(), "0".into()],
            &["`balance levels`", "at least 1"],
        ),
        (
            vec!["--feature-weight".into(), "401".into()],
            &["--feature-weight", "401", "0..=400"],
        ),
    ];
    for (extra, needles) in cases {
        let (ok, _, err) = run(lazysolid()
            .arg("solid")
            .arg(&good)
            .args(&extra)
            .arg("-o")
            .arg(&out));
        assert!(!ok, "{extra:?}");
        for needle in needles {
            assert!(
                err.contains(needle),
                "{extra:?}: missing {needle:?} in {err}"
            );
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists());
    }
    let png_out = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("solid").arg(&good).arg("-o").arg(&png_out));
    assert!(!ok && err.contains(".nrrd"), "{err}");
    assert!(!png_out.exists());
    // Nothing but the inputs in the folder.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
}
