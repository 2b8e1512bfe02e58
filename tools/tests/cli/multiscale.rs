//! `lazysolid multiscale` and `lazysolid zoom`, tested together on one exemplar graph: the window
//! (GPU and CPU equal) and the zoom frames are written, and a bad graph fails by file and line.

use crate::support::{lazysolid, run};

/// `lazysolid multiscale` and `lazysolid zoom` on a loop graph: the window and the frames are
/// written, and a bad graph fails with its file, line and field and leaves no output.
#[test]
fn multiscale_and_zoom_write_their_images_and_bad_graphs_fail_by_line() {
    let dir = tempfile::tempdir().unwrap();
    let graph = dir.path().join("g.toml");
    let text = "root = \"terra\"\n\n[[exemplar]]\nname = \"terra\"\nimage = \"terra\"\n\n\
                [[edge]]\nsource = \"terra\"\ndestination = \"terra\"\nr = 1\n";
    std::fs::write(&graph, text).unwrap();
    // GPU (with validation) and the CPU reference write the same image.
    let mut images = Vec::new();
    for extra in [&[][..], &["--cpu"][..]] {
        let out = dir.path().join(format!("out{}.png", images.len()));
        let (ok, stdout, err) = run(lazysolid()
            .arg("multiscale")
            .arg(&graph)
            .args(["--level", "8", "--res", "24x16", "--offset", "-5,3"])
            .args(extra)
            .arg("-o")
            .arg(&out)
            .env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        assert!(
            stdout.contains("exemplar terra") && stdout.contains("100.0 %"),
            "{stdout}"
        );
        let image = image::open(&out).unwrap();
        assert_eq!((image.width(), image.height()), (24, 16));
        assert!(out.with_extension("exemplars.png").exists());
        images.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(images[0], images[1]);
    let zoom = dir.path().join("zoom");
    let (ok, _, err) = run(lazysolid()
        .arg("zoom")
        .arg(&graph)
        .args([
            "--from",
            "5",
            "--to",
            "6.5",
            "--frame-count",
            "3",
            "--res",
            "16x12",
        ])
        .arg("--out-dir")
        .arg(&zoom));
    assert!(ok, "{err}");
    for f in [
        "frame_0000.png",
        "frame_0001.png",
        "frame_0002.png",
        "zoom.gif",
    ] {
        assert!(zoom.join(f).exists(), "{f}");
    }
    // r at r_max (terra is 64², L = 6: r_max = 3), named by file, line and field.
    std::fs::write(&graph, text.replace("r = 1", "r = 3")).unwrap();
    let out = dir.path().join("bad.png");
    let (ok, _, err) = run(lazysolid()
        .arg("multiscale")
        .arg(&graph)
        .args(["--level", "3", "-o"])
        .arg(&out));
    assert!(!ok);
    assert!(err.contains("g.toml:10: edge #1.r: r = 3"), "{err}");
    assert!(!err.contains("panicked") && !out.exists(), "{err}");
}
