//! FLIP comparison: zero for identical images, growing with the difference, and clear errors
//! for images that cannot be compared.

use image::{Rgb, RgbImage, Rgba, RgbaImage};
use lazysolid_renderer::diff::{flip_files, flip_images, DiffError};

/// A 64x48 image with gradients and a checker pattern, so FLIP's edge and colour terms both
/// have something to see.
fn reference() -> RgbImage {
    RgbImage::from_fn(64, 48, |x, y| {
        let checker = if (x / 8 + y / 8) % 2 == 0 { 40 } else { 0 };
        Rgb([
            (x * 3) as u8 + checker,
            (y * 4) as u8 + checker,
            ((x + y) * 2) as u8,
        ])
    })
}

/// The reference with the first `n` pixels of a diagonal-ish scatter turned white.
fn with_changed_pixels(n: u32) -> RgbImage {
    let mut image = reference();
    for i in 0..n {
        let x = (i * 7) % 64;
        let y = (i * 13 + i / 64) % 48;
        image.put_pixel(x, y, Rgb([255, 255, 255]));
    }
    image
}

#[test]
fn identical_images_have_zero_error() {
    let r = flip_images(&reference(), &reference()).unwrap();
    assert_eq!((r.width, r.height), (64, 48));
    assert_eq!(r.mean, 0.0);
    assert_eq!(r.max, 0.0);
    assert_eq!(r.p99, 0.0);
    // Every pixel is magma(0), the near-black start of the colour map.
    assert!(r.error_map.pixels().all(|p| p.0 == [0, 0, 4]));
}

#[test]
fn error_grows_with_the_difference() {
    let few = flip_images(&reference(), &with_changed_pixels(3)).unwrap();
    assert!(few.mean > 0.0 && few.max > 0.0, "{few:?}");
    // Three pixels of 3072, each smeared over a small neighbourhood by FLIP's filters: a small
    // mean, a median of zero, a clearly visible maximum.
    // (Measured: mean 0.0083, max 0.99.)
    assert!(few.mean < 0.02, "{}", few.mean);
    assert_eq!(few.median, 0.0);
    assert!(few.max > 0.3, "{}", few.max);

    let inverted = RgbImage::from_fn(64, 48, |x, y| {
        let Rgb([r, g, b]) = *reference().get_pixel(x, y);
        Rgb([255 - r, 255 - g, 255 - b])
    });
    let very = flip_images(&reference(), &inverted).unwrap();
    assert!(
        very.mean > 0.3 && very.mean > 30.0 * few.mean,
        "{} vs {}",
        very.mean,
        few.mean
    );
    assert!(very.median > 0.2, "{}", very.median);

    let means: Vec<f32> = [3, 12, 48, 192, 768]
        .into_iter()
        .map(|n| {
            flip_images(&reference(), &with_changed_pixels(n))
                .unwrap()
                .mean
        })
        .collect();
    assert!(
        means.windows(2).all(|w| w[0] < w[1]),
        "more changed pixels, larger mean: {means:?}"
    );
    for r in [&few, &very] {
        assert!(
            r.median <= r.p95 && r.p95 <= r.p99 && r.p99 <= r.max,
            "{r:?}"
        );
    }
}

#[test]
fn files_compare_like_images_and_alpha_is_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let reference_path = dir.path().join("reference.png");
    let test_path = dir.path().join("test.png");
    reference().save(&reference_path).unwrap();
    // The same colours with a varying alpha: alpha must not count.
    let rgba = RgbaImage::from_fn(64, 48, |x, y| {
        let Rgb([r, g, b]) = *with_changed_pixels(12).get_pixel(x, y);
        Rgba([r, g, b, (x * 4) as u8])
    });
    rgba.save(&test_path).unwrap();
    let from_files = flip_files(&reference_path, &test_path).unwrap();
    let from_memory = flip_images(&reference(), &with_changed_pixels(12)).unwrap();
    assert_eq!(from_files.mean, from_memory.mean);
    assert_eq!(from_files.max, from_memory.max);
    assert_eq!(from_files.error_map, from_memory.error_map);

    let map_path = dir.path().join("error.png");
    from_files.write_error_map(&map_path).unwrap();
    assert_eq!(
        image::open(&map_path).unwrap().into_rgb8(),
        from_files.error_map
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        3,
        "no temporary file left"
    );
}

#[test]
fn size_mismatch_names_both_files_and_sizes() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("wide.png");
    let b = dir.path().join("small.png");
    reference().save(&a).unwrap();
    RgbImage::new(32, 16).save(&b).unwrap();
    let err = flip_files(&a, &b).unwrap_err();
    assert!(matches!(err, DiffError::SizeMismatch { .. }));
    let message = err.to_string();
    assert!(
        message.contains(&a.display().to_string())
            && message.contains("64x48")
            && message.contains(&b.display().to_string())
            && message.contains("32x16"),
        "{message}"
    );
    let err = flip_images(&reference(), &RgbImage::new(64, 47))
        .unwrap_err()
        .to_string();
    assert!(err.contains("64x48") && err.contains("64x47"), "{err}");
    let err = flip_images(&RgbImage::new(0, 5), &RgbImage::new(0, 5))
        .unwrap_err()
        .to_string();
    assert!(err.contains("0x5") && err.contains("no pixels"), "{err}");
}

#[test]
fn missing_or_unreadable_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.png");
    reference().save(&good).unwrap();
    let missing = dir.path().join("missing.png");
    let err = flip_files(&good, &missing).unwrap_err().to_string();
    assert!(
        err.contains("missing.png") && err.contains("cannot open"),
        "{err}"
    );
    let err = flip_files(&missing, &good).unwrap_err().to_string();
    assert!(err.contains("missing.png"), "{err}");

    let garbage = dir.path().join("garbage.png");
    std::fs::write(&garbage, b"not an image at all").unwrap();
    let err = flip_files(&good, &garbage).unwrap_err().to_string();
    assert!(
        err.contains("garbage.png") && err.contains("cannot decode"),
        "{err}"
    );

    let map = dir.path().join("no-such-folder").join("map.png");
    let report = flip_images(&reference(), &reference()).unwrap();
    let err = report.write_error_map(&map).unwrap_err().to_string();
    assert!(err.contains("no-such-folder"), "{err}");
}

#[test]
fn hdr_images_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("linear.exr");
    let film = lazysolid_renderer::output::Film::black(8, 8).unwrap();
    lazysolid_renderer::output::write_exr(&film, &exr).unwrap();
    let png = dir.path().join("display.png");
    RgbImage::new(8, 8).save(&png).unwrap();
    let err = flip_files(&png, &exr).unwrap_err().to_string();
    assert!(
        err.contains("linear.exr") && err.contains("tone-map"),
        "{err}"
    );
}
