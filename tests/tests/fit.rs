//! Any photo as exemplar: GIMP stones of five sizes and photos written as PNG and JPEG with
//! every channel layout get the handling `fit.rs` states, the handling line says it, what
//! cannot be fitted is refused naming the file and the limit, the caches key the fitted
//! pixels, and a non-square, non-power-of-two photo synthesizes on the GPU exactly as on the
//! CPU reference.

use image::{GrayAlphaImage, ImageBuffer, Rgb, RgbImage, RgbaImage};
use lazysolid_synth::solid::{candidates_key, CandidateParams, SolidExemplars};
use lazysolid_synth::{
    analyze, default_jitter, default_passes, load_plane, load_solid, synthesize_cpu,
    AnalysisParams, Border, ChannelLayout, DecodedImage, Exemplar, FitMode, GpuSynthesizer, Region,
    SynthError, SynthParams,
};
use lazysolid_tests::{asset_exemplar, exemplar_crop, with_gpu};
use std::path::{Path, PathBuf};

/// A GIMP pattern of the assets as an `image` RGB image.
fn pattern(file: &str) -> RgbImage {
    let e = Exemplar::load(&asset_exemplar(file)).unwrap_or_else(|e| panic!("{e}"));
    RgbImage::from_fn(e.width, e.height, |x, y| Rgb(e.at(x, y)))
}

/// `image` saved as `name` in `dir`.
fn save<P, C>(dir: &Path, name: &str, image: &ImageBuffer<P, C>) -> PathBuf
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let path = dir.join(name);
    image.save(&path).unwrap();
    path
}

#[test]
fn gimp_stones_of_every_size_get_the_stated_handling() {
    for (file, line) in [
        ("slate.pat", "slate.pat 128x128 grey, native"),
        ("marble1.pat", "marble1.pat 128x128 grey, native"),
        (
            "Craters.pat",
            "Craters.pat 115x115 RGB → Lanczos3 resample 128x128",
        ),
        (
            "cracked.pat",
            "cracked.pat 144x144 RGB → centre crop 128x128 at (8, 8)",
        ),
        (
            "stone33.pat",
            "stone33.pat 156x156 RGB → centre crop 128x128 at (14, 14)",
        ),
        (
            "ground1.pat",
            "ground1.pat 100x100 RGB → Lanczos3 resample 128x128",
        ),
    ] {
        let path = asset_exemplar(file);
        let solid = load_solid(&path, FitMode::Auto, None).unwrap();
        assert_eq!(solid.fit.to_string(), line);
        assert_eq!((solid.exemplar.width, solid.exemplar.height), (128, 128));
        // 2D takes every one of them as it is.
        let plane = load_plane(&path, Border::Wrap).unwrap();
        assert!(plane.fit.is_native(), "{}", plane.fit);
        let original = Exemplar::load(&path).unwrap();
        assert_eq!(plane.exemplar.rgb, original.rgb, "{file}");
        // Grey is replicated to RGB.
        if file == "slate.pat" {
            assert!(plane
                .exemplar
                .rgb
                .iter()
                .all(|p| p[0] == p[1] && p[1] == p[2]));
        }
        // A crop keeps the pixels; a resample keeps the colours (mean within 2 levels).
        if let Some(c) = solid.fit.plan.crop {
            assert_eq!(solid.exemplar.at(0, 0), original.at(c.x, c.y));
            assert_eq!(
                solid.exemplar.at(127, 127),
                original.at(c.x + 127, c.y + 127)
            );
        } else if solid.fit.plan.resample.is_some() {
            let mean = |e: &Exemplar| {
                let n = e.rgb.len() as f64;
                [0, 1, 2].map(|c| e.rgb.iter().map(|p| p[c] as f64).sum::<f64>() / n)
            };
            let (a, b) = (mean(&original), mean(&solid.exemplar));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 2.0, "{file}: {a:?} vs {b:?}");
            }
        }
    }
    // 144² and 100² at 128 (bench solid's --side), and Craters at 16 by each mode.
    let fit = |file: &str, mode, side| {
        load_solid(&asset_exemplar(file), mode, side)
            .unwrap()
            .fit
            .to_string()
    };
    assert_eq!(
        fit("ground1.pat", FitMode::Auto, Some(128)),
        "ground1.pat 100x100 RGB → Lanczos3 resample 128x128"
    );
    assert_eq!(
        fit("Craters.pat", FitMode::Crop, Some(16)),
        "Craters.pat 115x115 RGB → centre crop 16x16 at (49, 49)"
    );
    assert_eq!(
        fit("Craters.pat", FitMode::Resample, None),
        "Craters.pat 115x115 RGB → Lanczos3 resample 128x128"
    );
    assert_eq!(
        fit("Craters.pat", FitMode::Crop, None),
        "Craters.pat 115x115 RGB → centre crop 64x64 at (25, 25)"
    );
}

#[test]
fn photos_in_png_and_jpeg_with_any_channels_load() {
    let dir = tempfile::tempdir().unwrap();
    let stone = pattern("stone33.pat");
    let crop = |x, y, w, h| image::imageops::crop_imm(&stone, x, y, w, h).to_image();
    // RGBA: a 100² crop with a varying alpha, which is dropped.
    let rgb = crop(20, 20, 100, 100);
    let rgba = RgbaImage::from_fn(100, 100, |x, y| {
        let [r, g, b] = rgb.get_pixel(x, y).0;
        image::Rgba([r, g, b, (x + y) as u8])
    });
    let rgba_path = save(dir.path(), "stone-rgba.png", &rgba);
    // Grey and alpha, from the cracked pattern.
    let cracked = image::DynamicImage::ImageRgb8(pattern("cracked.pat")).to_luma8();
    let grey_alpha = GrayAlphaImage::from_fn(144, 144, |x, y| {
        image::LumaA([cracked.get_pixel(x, y).0[0], 255 - x as u8])
    });
    let la_path = save(dir.path(), "cracked-la.png", &grey_alpha);
    // 16-bit RGB, reduced to 8.
    let deep: ImageBuffer<Rgb<u16>, Vec<u16>> = ImageBuffer::from_fn(40, 40, |x, y| {
        Rgb(stone.get_pixel(x, y).0.map(|v| v as u16 * 257))
    });
    let deep_path = save(dir.path(), "stone-16bit.png", &deep);
    // A 200×150 JPEG of the resampled cracked pattern.
    let photo = image::imageops::resize(
        &pattern("cracked.pat"),
        200,
        150,
        image::imageops::FilterType::Lanczos3,
    );
    let jpeg_path = save(dir.path(), "cracked.jpg", &photo);

    let read = |p: &Path| DecodedImage::read(p).unwrap();
    assert_eq!(read(&rgba_path).layout, ChannelLayout::Rgba);
    assert_eq!(read(&la_path).layout, ChannelLayout::GreyAlpha);
    let d = read(&deep_path);
    assert_eq!(d.layout, ChannelLayout::Rgb);
    assert_eq!(d.rgb[41], stone.get_pixel(1, 1).0);
    let j = read(&jpeg_path);
    assert_eq!(
        (j.width, j.height, j.layout),
        (200, 150, ChannelLayout::Rgb)
    );
    // The RGBA file's colours are the crop's, exactly.
    assert_eq!(read(&rgba_path).rgb[0], rgb.get_pixel(0, 0).0);

    let solid = |p: &Path| load_solid(p, FitMode::Auto, None).unwrap().fit.to_string();
    assert_eq!(
        solid(&rgba_path),
        "stone-rgba.png 100x100 RGBA, alpha dropped → Lanczos3 resample 128x128"
    );
    assert_eq!(
        solid(&la_path),
        "cracked-la.png 144x144 grey+alpha, alpha dropped → centre crop 128x128 at (8, 8)"
    );
    assert_eq!(
        solid(&deep_path),
        "stone-16bit.png 40x40 RGB → centre crop 32x32 at (4, 4)"
    );
    assert_eq!(
        solid(&jpeg_path),
        "cracked.jpg 200x150 RGB → centre crop 128x128 at (36, 11)"
    );
    let plane = |p: &Path| load_plane(p, Border::Wrap).unwrap().fit.to_string();
    assert_eq!(
        plane(&rgba_path),
        "stone-rgba.png 100x100 RGBA, alpha dropped, native"
    );
    assert_eq!(plane(&jpeg_path), "cracked.jpg 200x150 RGB, native");
}

#[test]
fn what_cannot_be_fitted_is_refused_naming_the_file_and_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let stone = pattern("stone33.pat");
    let thin = save(
        dir.path(),
        "thin.png",
        &image::imageops::crop_imm(&stone, 0, 0, 12, 40).to_image(),
    );
    for e in [
        load_solid(&thin, FitMode::Auto, None).unwrap_err(),
        load_solid(&thin, FitMode::Resample, Some(16)).unwrap_err(),
        load_plane(&thin, Border::Wrap).unwrap_err(),
    ] {
        assert!(
            matches!(
                e,
                SynthError::Fit {
                    width: 12,
                    height: 40,
                    ..
                }
            ),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("thin.png") && msg.contains("12x40") && msg.contains("at least 16"),
            "{msg}"
        );
    }
    // A crop needs the side it cuts.
    let small = save(
        dir.path(),
        "small.png",
        &image::imageops::crop_imm(&stone, 0, 0, 100, 100).to_image(),
    );
    let msg = load_solid(&small, FitMode::Crop, Some(128))
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("small.png") && msg.contains("--fit crop") && msg.contains("128"),
        "{msg}"
    );
    // Past the decode limit, before any pixel is decoded.
    let wide = save(dir.path(), "wide.png", &RgbImage::new(9000, 16));
    let msg = load_plane(&wide, Border::Wrap).unwrap_err().to_string();
    assert!(
        msg.contains("wide.png") && msg.contains("9000x16") && msg.contains("8192"),
        "{msg}"
    );
    // Too elongated to shrink to 512 and keep 16.
    let strip = save(dir.path(), "strip.png", &RgbImage::new(2000, 40));
    let msg = load_plane(&strip, Border::Wrap).unwrap_err().to_string();
    assert!(msg.contains("strip.png") && msg.contains("512x10"), "{msg}");
}

#[test]
fn the_caches_key_the_fitted_pixels() {
    let path = asset_exemplar("stone33.pat");
    let key = |e: Exemplar| {
        candidates_key(
            &SolidExemplars::new(e, [None, None, None]).unwrap(),
            &CandidateParams::default(),
        )
    };
    let cropped = load_solid(&path, FitMode::Auto, None).unwrap().exemplar;
    // The same pixels cut by hand: the same entry.
    assert_eq!(
        key(cropped),
        key(exemplar_crop("stone33.pat", 14, 14, 128, 128))
    );
    // The same file fitted another way: another entry.
    let resample = || load_solid(&path, FitMode::Resample, None).unwrap().exemplar;
    assert_ne!(
        key(resample()),
        key(exemplar_crop("stone33.pat", 14, 14, 128, 128))
    );
    // A resample is the same on every run, so its entry is found again.
    assert_eq!(key(resample()), key(resample()));
}

#[test]
fn a_non_square_photo_synthesizes_on_the_gpu_as_on_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let photo = save(
        dir.path(),
        "stone137x99.png",
        &image::imageops::crop_imm(&pattern("stone33.pat"), 10, 30, 137, 99).to_image(),
    );
    let fitted = load_plane(&photo, Border::Wrap).unwrap();
    assert_eq!(fitted.fit.to_string(), "stone137x99.png 137x99 RGB, native");
    let analysis = analyze(&fitted.exemplar, &AnalysisParams::default()).unwrap();
    // floor(log2(99)) = 6: seven levels.
    let levels = analysis.levels.len() as u32;
    assert_eq!(levels, 7);
    let params =
        SynthParams::new(levels, 5, &default_passes(levels), &default_jitter(levels)).unwrap();
    let window = Region {
        origin: [-5, 7],
        size: [24, 20],
    };
    let cpu = synthesize_cpu(&analysis, &params, window).unwrap();
    let gpu = with_gpu(|gpu| {
        GpuSynthesizer::new(gpu, &analysis)
            .unwrap()
            .synthesize(&analysis, &params, window, false, &mut |_| {})
            .unwrap()
    });
    assert_eq!(cpu.window_coords(), gpu.window_coords());
    // Every coordinate lies in the exemplar.
    assert!(cpu
        .window_coords()
        .iter()
        .all(|&c| (c & 0xffff) < 137 && (c >> 16) < 99));
}
