//! `lazysolid render`: the PNG and EXR of a scene, the frames of an animated one, and bad scenes
//! and arguments refused before anything is written.

use crate::support::{lazysolid, repo, run};

#[test]
fn render_writes_png_and_exr_and_says_where() {
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("interior.png");
    let (ok, stdout, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/interior.toml"))
        .arg("-o")
        .arg(&png)
        .args(["--spp", "2", "--res", "40x30"])
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    assert!(stdout.contains(&png.display().to_string()), "{stdout}");
    assert!(err.contains("Mrays/s"), "{err}");
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (40, 30));
    assert!(out.path().join("interior.exr").exists());
}

#[test]
fn render_refuses_bad_scenes_and_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov_y = 40\n\n[render]\nwidth = 8\nheight = 8\nspp = 1\nfocus = 2\n",
    )
    .unwrap();
    let png = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("render").arg(&scene).arg("-o").arg(&png));
    assert!(!ok);
    assert!(
        err.contains("bad.toml:10") && err.contains("focus"),
        "the unknown key is named with its line: {err}"
    );
    assert!(!png.exists(), "no image is written for a bad scene");
    let (ok, _, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/interior.toml"))
        .arg("-o")
        .arg(&png)
        .args(["--res", "40by30"]));
    assert!(
        !ok && err.contains("WxH") && err.contains("40by30"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid()
        .arg("render")
        .arg(dir.path().join("missing.toml"))
        .arg("-o")
        .arg(&png));
    assert!(!ok && err.contains("missing.toml"), "{err}");
    // Another view of a scene: a camera that looks at itself, a field of view out of range and
    // a point that is not X,Y,Z are refused before anything is written.
    for (args, want) in [
        (
            &["--camera", "0,1,2", "--look-at", "0,1,2"][..],
            "the camera is at the point it looks at",
        ),
        (&["--fov", "180"][..], "--fov 180 is out of range"),
        (&["--look-at", "1,2"][..], "is not X,Y,Z"),
        (
            &["--camera", "0,5,0", "--look-at", "0,0,0"][..],
            "parallel to the camera's up",
        ),
    ] {
        let (ok, _, err) = run(lazysolid()
            .arg("render")
            .arg(repo("scenes/test/interior.toml"))
            .arg("-o")
            .arg(&png)
            .args(args));
        assert!(!ok && err.contains(want), "{args:?}: {err}");
        assert!(!png.exists(), "{args:?}");
    }
}

/// `render --frame K --frames A..B` renders the still and the sequence from one bake: the still
/// (PNG and EXR), numbered PNGs, and an animated GIF with one image per frame. A scene without
/// [animation] and a frame past its last are refused before anything is rendered.
#[test]
fn render_frames_writes_a_still_numbered_frames_and_a_gif() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("boom.png");
    let (ok, stdout, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/fracture.toml"))
        .args([
            "--frame", "1", "--frames", "0..2", "--res", "32x24", "--spp", "2", "-o",
        ])
        .arg(&out)
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    for needle in [
        "[[instance]] 1 (bunny): broken into 6 closed pieces\n",
        "cut faces:",
        "frame 1 (t = 0.250 s): 32x24, 2 spp",
        "frame 2 (t = 0.500 s)",
        "total",
    ] {
        assert!(err.contains(needle), "{needle:?} not in {err}");
    }
    assert!(
        stdout.contains("animation:") && stdout.contains("boom.gif"),
        "{stdout}"
    );
    for f in [
        "boom.png",
        "boom.exr",
        "boom_0000.png",
        "boom_0001.png",
        "boom_0002.png",
    ] {
        assert!(dir.path().join(f).is_file(), "{f} missing");
    }
    assert!(!dir.path().join("boom_0003.png").exists());
    let gif = std::fs::read(dir.path().join("boom.gif")).unwrap();
    assert!(gif.starts_with(b"GIF89a"));
    // One graphic control extension (the frame delay) per frame.
    let frames = gif.windows(2).filter(|w| w == &[0x21, 0xf9]).count();
    assert_eq!(frames, 3, "GIF frames");

    let refused = dir.path().join("refused.png");
    for (scene, args, needle) in [
        (
            "scenes/test/synthesized.toml",
            vec!["--frames", "0..1"],
            "has no [animation]",
        ),
        (
            "scenes/test/fracture.toml",
            vec!["--frame", "4"],
            "frame 4 is past the scene's last frame 3",
        ),
        (
            "scenes/test/fracture.toml",
            vec!["--frames", "2..1"],
            "the first frame is after the last",
        ),
    ] {
        let (ok, _, err) = run(lazysolid()
            .arg("render")
            .arg(repo(scene))
            .args(&args)
            .arg("-o")
            .arg(&refused));
        assert!(!ok && err.contains(needle), "{args:?}: {err}");
        assert!(!refused.exists());
    }
}

/// A scanned mesh that intersects itself (the cow) breaks in a scene as it does in
/// `lazysolid fracture`: every piece closed, and the load says how many crossings of its
/// surface the caps resolved.
#[test]
fn render_says_how_many_crossings_a_broken_scan_resolved() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("cow.toml");
    std::fs::write(
        &scene,
        format!(
            r#"[camera]
position = [-2.0, 1.2, 2.0]
look_at = [0.5, 0.4, 0.5]
fov_y = 40

[render]
width = 16
height = 12
spp = 1

[[mesh]]
name = "cow"
path = "{}"

[[material]]
name = "grey"
kind = "lambertian"
color = [0.5, 0.5, 0.5]

[[instance]]
name = "cow"
mesh = "cow"
material = "grey"

[[fracture]]
instance = "cow"
pieces = 12
seed = 1

[environment]
radiance = [0.5, 0.5, 0.5]
"#,
            repo("assets/meshes/cow.off").display()
        ),
    )
    .unwrap();
    let (ok, _, err) = run(lazysolid()
        .arg("render")
        .arg(&scene)
        .arg("-o")
        .arg(dir.path().join("cow.png")));
    assert!(ok, "{err}");
    let line = err
        .lines()
        .find(|l| l.starts_with("[[instance]] 1 (cow): broken into 12 closed pieces; "))
        .unwrap_or_else(|| panic!("no pieces line in {err}"));
    let crossings: usize = line
        .split("; ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no count in {line}"));
    assert!(crossings > 0, "{line}");
    assert!(
        line.ends_with("; its sheets separated where they met (2 vertex copies and edge splits)"),
        "{line}"
    );
}

/// Writes a `width`×`height` grey height map of round bumps to `path`.
fn bumps(path: &std::path::Path, width: u32, height: u32) {
    let map = image::GrayImage::from_fn(width, height, |x, y| {
        let (u, v) = (x as f32 * 0.35, y as f32 * 0.45);
        image::Luma([(127.5 + 120.0 * (u.sin() * v.cos())) as u8])
    });
    map.save(path).unwrap();
}

#[test]
fn height_maps_of_any_size_render_under_every_filter_with_their_fit() {
    let dir = tempfile::tempdir().unwrap();
    // 100² is resampled to 128² (a crop would lose over a quarter of it), 200×150 is cut to its
    // centre 128²: the exemplar rule (`synth/src/fit.rs`).
    let cases = [
        (
            "h100.png",
            100,
            100,
            "h100.png 100x100 grey → Lanczos3 resample 128x128, heights x1.2800 (slopes kept)",
        ),
        (
            "h200x150.png",
            200,
            150,
            "h200x150.png 200x150 grey → centre crop 128x128 at (36, 11)",
        ),
    ];
    for (name, width, height, fit) in cases {
        bumps(&dir.path().join(name), width, height);
        let mut scene = String::from(
            "[camera]\nposition = [0.0, 1.4, 1.2]\nlook_at = [0.0, 0.0, 0.0]\nfov_y = 60\n\
             [render]\nwidth = 48\nheight = 32\nspp = 1\nmax_depth = 2\n\
             [[mesh]]\nname = \"plane\"\nshape = \"quad\"\n\
             [[light]]\nkind = \"sphere\"\ncenter = [0.0, 2.0, -1.5]\nradius = 0.3\n\
             radiance = [200.0, 200.0, 200.0]\n",
        );
        for (k, filter) in ["none", "mip", "vmf"].iter().enumerate() {
            scene += &format!(
                "[[material]]\nname = \"{filter}\"\nkind = \"conductor\"\npreset = \"silver\"\n\
                 roughness = 0.3\nheight_map = \"{name}\"\nnormal_filter = \"{filter}\"\n\
                 [[instance]]\nmesh = \"plane\"\nmaterial = \"{filter}\"\nscale = 0.55\n\
                 translate = [{}, 0.0, -0.3]\n",
                k as f32 * 0.6 - 1.2
            );
        }
        scene += &format!(
            "[[material]]\nname = \"glint\"\nkind = \"glint\"\npreset = \"aluminium\"\n\
             height_map = \"{name}\"\nintrinsic_roughness = 0.02\nscale = 0.55\nuv = \"planar\"\n\
             [[instance]]\nmesh = \"plane\"\nmaterial = \"glint\"\nscale = 0.55\n\
             translate = [0.6, 0.0, -0.3]\n"
        );
        let scene_file = dir.path().join(format!("{name}.toml"));
        std::fs::write(&scene_file, scene).unwrap();
        let output = dir.path().join(format!("{name}.out.png"));
        let (ok, _, err) = run(lazysolid()
            .arg("render")
            .arg(&scene_file)
            .arg("-o")
            .arg(&output)
            .env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        for material in ["none", "mip", "vmf"] {
            let line = format!("material {material:?}: normal map {fit}");
            assert!(err.contains(&line), "missing {line:?} in:\n{err}");
        }
        let line = format!("material \"glint\": glint example {fit}");
        assert!(err.contains(&line), "missing {line:?} in:\n{err}");
        assert!(output.exists());
    }
}
