//! Photos of any size as exemplars, as a user runs them: a 100×100 and a 200×150 PNG cut and
//! resampled from real stone patterns synthesize in 2D (`lazysolid synth`) and in 3D
//! (`lazysolid solid`), each run printing how the image became the exemplar.

use crate::support::{lazysolid, run};
use std::path::{Path, PathBuf};
use std::process::Command;

/// [`lazysolid`] with the validation layer on; the run must succeed. Returns its standard
/// output.
fn run_validated(c: &mut Command) -> String {
    let (ok, stdout, stderr) = run(c.env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{stderr}");
    stdout
}

/// A GIMP pattern of the assets as an RGB image (decoded by the library: the `image` crate
/// does not read patterns).
fn pattern(name: &str) -> image::RgbImage {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets/exemplars")
        .join(name);
    assert!(
        path.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        path.display()
    );
    let e = lazysolid_synth::Exemplar::load(&path).unwrap();
    image::RgbImage::from_fn(e.width, e.height, |x, y| image::Rgb(e.at(x, y)))
}

/// The two photos of the issue in `dir`: a 100×100 crop of GIMP's stone33 (156²) and GIMP's
/// cracked (144²) resampled to 200×150, i.e. stretched along x as a camera's 4:3 frame.
fn photos(dir: &Path) -> (PathBuf, PathBuf) {
    let square = dir.join("stone100.png");
    image::imageops::crop_imm(&pattern("stone33.pat"), 20, 30, 100, 100)
        .to_image()
        .save(&square)
        .unwrap();
    let wide = dir.join("cracked200x150.png");
    image::imageops::resize(
        &pattern("cracked.pat"),
        200,
        150,
        image::imageops::FilterType::Lanczos3,
    )
    .save(&wide)
    .unwrap();
    (square, wide)
}

fn assert_has(stdout: &str, needle: &str) {
    assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
}

fn size(path: &Path) -> (u32, u32) {
    let i = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (i.width(), i.height())
}

#[test]
fn synth_takes_both_photos_as_they_are() {
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let (square, wide) = photos(dir.path());
    for (photo, line, levels) in [
        (
            &square,
            "exemplar fit: stone100.png 100x100 RGB, native",
            "(100x100, 7 levels",
        ),
        (
            &wide,
            "exemplar fit: cracked200x150.png 200x150 RGB, native",
            "(200x150, 8 levels",
        ),
    ] {
        let out = dir.path().join("out.png");
        let stdout = run_validated(
            lazysolid()
                .arg("synth")
                .arg(photo)
                .args(["--res", "40x24", "--energy-samples", "16", "-o"])
                .arg(&out)
                .env("LAZYSOLID_CACHE_DIR", cache.path()),
        );
        assert_has(&stdout, line);
        assert_has(&stdout, levels);
        assert_has(&stdout, "cache miss");
        assert_eq!(size(&out), (40, 24));
        assert_eq!(size(&dir.path().join("out.coords.png")), (40, 24));
    }
}

#[test]
fn solid_fits_both_photos_and_says_how() {
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let (square, wide) = photos(dir.path());
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("stone.nrrd");
    let solid = |args: &[&std::ffi::OsStr]| {
        run_validated(
            lazysolid()
                .arg("solid")
                .args(args)
                // The smallest cube and one correction pass: the synthesizer itself is tested in
                // tests/tests/solid.rs.
                .args([
                    "--voxel-res",
                    "64",
                    "--passes",
                    "1",
                    "--energy-samples",
                    "16",
                ])
                .arg("--no-render")
                .arg("-o")
                .arg(&out)
                .env("LAZYSOLID_CACHE_DIR", cache.path()),
        )
    };
    // By default the two would become 128² exemplars (resampled and cut; the rules are tested
    // in tests/tests/fit.rs), whose candidates take minutes in this build: fitted to 16² here,
    // the 200×150 photo as the exemplar of the slices perpendicular to z, fitted to the side
    // the main exemplar got.
    let stdout = solid(&[
        square.as_os_str(),
        "--ez".as_ref(),
        wide.as_os_str(),
        "--exemplar-side".as_ref(),
        "16".as_ref(),
    ]);
    assert_has(
        &stdout,
        "exemplar fit: stone100.png 100x100 RGB → Lanczos3 resample 16x16\n",
    );
    assert_has(
        &stdout,
        "exemplar fit: cracked200x150.png 200x150 RGB → centre crop 150x150 at (25, 0) → \
         Lanczos3 resample 16x16\n",
    );
    assert_has(&stdout, "exemplars 16x16: E_x = ");
    assert_has(&stdout, "E_z = ");
    assert_has(&stdout, "slice perpendicular to z vs E_z");
    // The volume's header records the handling too (ASCII).
    let nrrd = std::fs::read(&out).unwrap();
    let header_end = nrrd.windows(2).position(|w| w == b"\n\n").unwrap() + 2;
    assert_eq!(nrrd.len() - header_end, 64 * 64 * 64 * 3);
    let header = std::str::from_utf8(&nrrd[..header_end]).unwrap();
    assert!(
        header.contains(
            "\n# exemplar fit: stone100.png 100x100 RGB -> Lanczos3 resample 16x16\n# exemplar fit: cracked200x150.png"
        ),
        "{header}"
    );
    for name in ["x", "y", "z", "oblique"] {
        assert_eq!(size(&out_dir.join(format!("stone.{name}.png"))), (64, 64));
    }

    // The default rule on a photo small enough to run at its own size: 20×18 → its centre
    // 16² (a cut loses at most a quarter of the side).
    let small = dir.path().join("stone20x18.png");
    image::imageops::resize(
        &image::open(&square).unwrap().to_rgb8(),
        20,
        18,
        image::imageops::FilterType::Lanczos3,
    )
    .save(&small)
    .unwrap();
    let stdout = solid(&[small.as_os_str()]);
    assert_has(
        &stdout,
        "exemplar fit: stone20x18.png 20x18 RGB → centre crop 16x16 at (2, 1)\n",
    );
    assert_has(&stdout, "exemplars 16x16: E_x = ");
}
