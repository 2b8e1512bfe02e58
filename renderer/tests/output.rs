//! Film, EXR and PNG output: exact round trips, the tone curve on known values, and the
//! errors for bad films and unwritable destinations.

use lazysolid_renderer::output::{
    read_exr_layer, read_exr_rgb, srgb_oetf, write_exr, write_layer_png, write_png, Film,
    LayerMapping, Operator, OutputError, ToneMap,
};

/// A 7x5 film whose values exercise the f32 range: tiny, fractional, large, zero.
fn test_film() -> Film {
    let (w, h) = (7u32, 5u32);
    let color = (0..w * h)
        .map(|i| {
            let i = i as f32;
            [i * 0.173_205_08, 1.0 / (i + 3.0), 70_000.0 + i * 1e-3]
        })
        .collect();
    Film::new(w, h, color).unwrap()
}

fn exr_channel_names(path: &std::path::Path) -> Vec<String> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).unwrap();
    assert_eq!(image.layer_data.len(), 1, "one single-part layer");
    image.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect()
}

#[test]
fn exr_round_trip_is_exact() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("film.exr");
    let film = test_film();
    write_exr(&film, &path).unwrap();
    let (w, h, pixels) = read_exr_rgb(&path).unwrap();
    assert_eq!((w, h), (7, 5));
    // f32 storage: bit-exact, including values above the f16 range.
    assert_eq!(pixels, film.color());
    assert_eq!(exr_channel_names(&path), ["B", "G", "R"]);
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file left: {left:?}");
}

#[test]
fn exr_holds_the_auxiliary_layers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("aov.exr");
    let film = test_film();
    let n = film.len();
    let albedo: Vec<[f32; 3]> = (0..n).map(|i| [0.1, 0.2, i as f32 / n as f32]).collect();
    let normal: Vec<[f32; 3]> = (0..n).map(|_| [0.0, -1.0, 0.0]).collect();
    let depth: Vec<f32> = (0..n)
        .map(|i| if i % 2 == 0 { f32::INFINITY } else { i as f32 })
        .collect();
    let film = film
        .with_albedo(albedo.clone())
        .unwrap()
        .with_normal(normal.clone())
        .unwrap()
        .with_depth(depth.clone())
        .unwrap();
    write_exr(&film, &path).unwrap();
    let mut names = exr_channel_names(&path);
    names.sort();
    assert_eq!(
        names,
        [
            "B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth.Z", "normal.X", "normal.Y",
            "normal.Z"
        ]
    );
    // The main image is still what read_exr_rgb finds, and a layer is read by its names.
    assert_eq!(read_exr_rgb(&path).unwrap().2, film.color());
    let (w, h, read_albedo) = read_exr_layer(&path, ["albedo.R", "albedo.G", "albedo.B"]).unwrap();
    assert_eq!(
        (w, h, read_albedo),
        (film.width(), film.height(), albedo.clone())
    );
    let err = read_exr_layer(&path, ["albedo.R", "albedo.G", "albedo.A"])
        .unwrap_err()
        .to_string();
    assert!(err.contains("albedo.R, albedo.G, albedo.A"), "{err}");
    // And every layer's samples are the ones given.
    let image = exr::prelude::read_all_flat_layers_from_file(&path).unwrap();
    let channel = |name: &str| -> Vec<f32> {
        image.layer_data[0]
            .channel_data
            .list
            .iter()
            .find(|c| c.name.eq(name))
            .unwrap()
            .sample_data
            .values_as_f32()
            .collect()
    };
    assert_eq!(
        channel("albedo.B"),
        albedo.iter().map(|p| p[2]).collect::<Vec<_>>()
    );
    assert_eq!(
        channel("normal.Y"),
        normal.iter().map(|p| p[1]).collect::<Vec<_>>()
    );
    assert_eq!(channel("depth.Z"), depth);
}

#[test]
fn exr_without_rgb_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("depth-only.exr");
    use exr::prelude::*;
    let layer = Layer::new(
        (2, 2),
        LayerAttributes::default(),
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(vec![AnyChannel::new("Z", FlatSamples::F32(vec![1.0; 4]))].into()),
    );
    Image::from_layer(layer).write().to_file(&path).unwrap();
    let err = read_exr_rgb(&path).unwrap_err().to_string();
    assert!(
        err.contains("depth-only.exr") && err.contains("R, G, B") && err.contains("found: Z"),
        "{err}"
    );
    let missing = dir.path().join("absent.exr");
    let err = read_exr_rgb(&missing).unwrap_err().to_string();
    assert!(
        err.contains("absent.exr") && err.contains("cannot open"),
        "{err}"
    );
}

/// Writes a one-row film through `tone_map` and reads the PNG back.
fn png_codes(values: &[[f32; 3]], tone_map: ToneMap) -> Vec<[u8; 3]> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("row.png");
    let film = Film::new(values.len() as u32, 1, values.to_vec()).unwrap();
    write_png(&film, &path, &tone_map).unwrap();
    let image = image::open(&path).unwrap();
    assert_eq!(image.color(), image::ColorType::Rgb8);
    image.into_rgb8().pixels().map(|p| p.0).collect()
}

#[test]
fn png_tone_mapping_of_known_values() {
    let clamp = ToneMap::default();
    assert_eq!(clamp.operator, Operator::Clamp);
    // 0 and 1 are the ends of the code range; 0.5 linear is sRGB 0.7354 -> 187.52 -> 188;
    // 0.0031308 (the knee) -> 10.31 -> 10; 0.22 -> 129.13 -> 129; above 1 clips; negatives
    // are black.
    assert_eq!(
        png_codes(
            &[[0.0, 1.0, 0.5], [4.0, -2.0, 0.0031308], [0.22, 0.0, 1.0]],
            clamp
        ),
        [[0, 255, 188], [255, 0, 10], [129, 0, 255]]
    );
    // +1 EV doubles before the curve: 0.25 is shown as 0.5, 0.5 as 1.
    let brighter = ToneMap {
        exposure_ev: 1.0,
        operator: Operator::Clamp,
    };
    assert_eq!(png_codes(&[[0.25, 0.5, 0.0]], brighter), [[188, 255, 0]]);
    let darker = ToneMap {
        exposure_ev: -2.0,
        operator: Operator::Clamp,
    };
    assert_eq!(png_codes(&[[2.0, 4.0, 0.0]], darker), [[188, 255, 0]]);
    // Reinhard: 1 -> 0.5 -> 188; infinity -> 1; nothing clips.
    let reinhard = ToneMap {
        exposure_ev: 0.0,
        operator: Operator::Reinhard,
    };
    assert_eq!(
        png_codes(&[[1.0, f32::INFINITY, 0.0], [3.0, 1e30, 0.0]], reinhard),
        [[188, 255, 0], [225, 255, 0]]
    );
}

#[test]
fn aces_fitted_is_a_monotonic_shoulder() {
    let aces = ToneMap {
        exposure_ev: 0.0,
        operator: Operator::AcesFitted,
    };
    assert_eq!(aces.apply([0.0; 3]), [0.0; 3], "black stays black");
    let mut previous = 0.0;
    for i in 1..=200 {
        let x = i as f32 * 0.1;
        let y = aces.apply([x; 3])[1];
        assert!(y > previous && y <= 1.0, "{x} -> {y}");
        previous = y;
    }
    // Known values of the fit on grey (computed in f64; tolerance 1e-4 for f32 evaluation):
    // 0.18 -> 0.10559, 1 -> 0.61912, 20 -> 0.99529.
    for (x, y) in [(0.18, 0.10559), (1.0, 0.61912), (20.0, 0.99529)] {
        let got = aces.apply([x; 3]);
        assert!(got.iter().all(|g| (g - y).abs() < 1e-4), "{x} -> {got:?}");
    }
    assert_eq!(aces.to_srgb8([f32::INFINITY; 3]), Some([255; 3]));
}

#[test]
fn srgb_oetf_matches_the_standard() {
    // Both branches and the knee; tolerance 1e-6 for f32 evaluation.
    for (x, y) in [
        (0.0, 0.0),
        (0.0031308, 0.040_449_936),
        (0.5, 0.735_356_6),
        (1.0, 1.0),
    ] {
        assert!((srgb_oetf(x) - y).abs() < 1e-6, "{x} -> {}", srgb_oetf(x));
    }
}

#[test]
fn nan_pixel_is_refused_with_its_position() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nan.png");
    let mut film = Film::black(4, 3).unwrap();
    film.color_mut()[2 * 4 + 1] = [0.0, f32::NAN, 0.0];
    let err = write_png(&film, &path, &ToneMap::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("nan.png") && err.contains("pixel (1, 2)") && err.contains("NaN"),
        "{err}"
    );
    assert!(!path.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // The EXR keeps what the PNG cannot show.
    let exr_path = dir.path().join("nan.exr");
    write_exr(&film, &exr_path).unwrap();
    assert!(read_exr_rgb(&exr_path).unwrap().2[9][1].is_nan());
}

#[test]
fn layer_pngs_map_albedo_and_normals() {
    let dir = tempfile::tempdir().unwrap();
    let albedo_path = dir.path().join("albedo.png");
    let normal_path = dir.path().join("normal.png");
    write_layer_png(
        &[[0.5, 1.0, 0.0], [2.0, 0.0, 0.22]],
        2,
        1,
        LayerMapping::Albedo,
        &albedo_path,
    )
    .unwrap();
    write_layer_png(
        &[[0.0, 1.0, -1.0], [0.6, -0.6, 0.0]],
        1,
        2,
        LayerMapping::Normal,
        &normal_path,
    )
    .unwrap();
    let codes = |p| -> Vec<[u8; 3]> {
        image::open(p)
            .unwrap()
            .into_rgb8()
            .pixels()
            .map(|p| p.0)
            .collect()
    };
    assert_eq!(codes(&albedo_path), [[188, 255, 0], [255, 0, 129]]);
    // (x + 1) / 2 * 255, rounded: 0 -> 128, 1 -> 255, -1 -> 0, 0.6 -> 204, -0.6 -> 51.
    assert_eq!(codes(&normal_path), [[128, 255, 0], [204, 51, 128]]);
    let err = write_layer_png(&[[0.0; 3]; 3], 2, 2, LayerMapping::Normal, &normal_path)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("normal layer has 3 pixels") && err.contains("needs 4"),
        "{err}"
    );
}

#[test]
fn film_length_mismatch_is_an_error() {
    let err = Film::new(4, 3, vec![[0.0; 3]; 11]).unwrap_err();
    assert!(matches!(
        err,
        OutputError::LayerLength {
            layer: "color",
            expected: 12,
            actual: 11,
            ..
        }
    ));
    assert_eq!(
        err.to_string(),
        "film color layer has 11 pixels, but a 4x3 film needs 12"
    );
    let film = Film::black(4, 3).unwrap();
    let err = film.clone().with_albedo(vec![[0.0; 3]; 13]).unwrap_err();
    assert!(
        err.to_string().contains("albedo layer has 13 pixels"),
        "{err}"
    );
    let err = film.clone().with_normal(vec![]).unwrap_err();
    assert!(
        err.to_string().contains("normal layer has 0 pixels"),
        "{err}"
    );
    let err = film.with_depth(vec![0.0; 24]).unwrap_err();
    assert!(
        err.to_string().contains("depth layer has 24 pixels"),
        "{err}"
    );
    let err = Film::new(0, 3, vec![]).unwrap_err();
    assert!(err.to_string().contains("0x3"), "{err}");
}

#[test]
fn missing_folder_leaves_no_file_and_names_it() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("not-there");
    let film = test_film();
    for (path, result) in [
        (folder.join("a.exr"), write_exr(&film, folder.join("a.exr"))),
        (
            folder.join("a.png"),
            write_png(&film, folder.join("a.png"), &ToneMap::default()),
        ),
    ] {
        let err = result.unwrap_err().to_string();
        assert!(
            err.contains(&path.display().to_string()) && err.contains("temporary file"),
            "{err}"
        );
        assert!(!path.exists());
    }
    assert!(!folder.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn failed_write_keeps_the_previous_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("keep.png");
    std::fs::write(&path, b"previous").unwrap();
    let mut film = Film::black(2, 2).unwrap();
    film.color_mut()[0][0] = f32::NAN;
    assert!(write_png(&film, &path, &ToneMap::default()).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), b"previous");
    // A successful write replaces it.
    film.color_mut()[0][0] = 1.0;
    write_png(&film, &path, &ToneMap::default()).unwrap();
    assert_eq!(
        image::open(&path).unwrap().into_rgb8().get_pixel(0, 0).0,
        [255, 0, 0]
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}
