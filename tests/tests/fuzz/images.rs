//! Exemplar images: GIMP patterns, PNG (8 and 16 bits, grey to RGBA), JPEG and GIF, decoded
//! (`DecodedImage::read`) and fitted both ways (`fit_solid`, `fit_plane`), as `synth`,
//! `solid` and the scenes' synthesized textures read them.

use crate::oracle::{self, MIB};
use crate::{mutate, FileFormat, Seed};
use image::{DynamicImage, ImageFormat};
use lazysolid_synth::{fit_plane, fit_solid, Border, DecodedImage, FitMode, MAX_DECODE_SIDE};
use lazysolid_tests::asset_exemplar;
use proptest::prelude::*;
use std::io::Cursor;
use std::path::Path;
use std::sync::OnceLock;

/// The most a decoder may hold for a header's size fields: a [`MAX_DECODE_SIDE`]² image of
/// 16-bit RGBA (what the `image` crate allocates before reading the pixels) and its 8-bit RGB
/// copy, with room for the decoder's own buffers.
const BOUND: usize = (MAX_DECODE_SIDE as usize).pow(2) * (8 + 3) + 64 * MIB;

fn read(path: &Path) -> Result<(), String> {
    let image = DecodedImage::read(path).map_err(|e| e.to_string())?;
    fit_solid(image.clone(), FitMode::Auto, None).map_err(|e| e.to_string())?;
    fit_plane(image, Border::Wrap).map_err(|e| e.to_string())?;
    Ok(())
}

fn encoded(image: DynamicImage, format: ImageFormat) -> Vec<u8> {
    let mut bytes = Cursor::new(Vec::new());
    image.write_to(&mut bytes, format).unwrap();
    bytes.into_inner()
}

/// Two patterns (RGB and grey, from the assets), and small images in every other format,
/// channel layout and depth the decoder takes, drawn from a pattern.
fn seeds() -> &'static [Seed] {
    static SEEDS: OnceLock<Vec<Seed>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let walnut = DecodedImage::read(&asset_exemplar("walnut.pat")).unwrap();
        let rgb = image::RgbImage::from_fn(40, 24, |x, y| {
            image::Rgb(walnut.rgb[(y * walnut.width + x) as usize])
        });
        let rgb = DynamicImage::ImageRgb8(rgb);
        vec![
            Seed::file(&asset_exemplar("walnut.pat")),
            Seed::file(&asset_exemplar("granite1.pat")),
            Seed {
                name: "rgba16.png".into(),
                bytes: encoded(DynamicImage::ImageRgba16(rgb.to_rgba16()), ImageFormat::Png),
            },
            Seed {
                name: "grey-alpha.png".into(),
                bytes: encoded(
                    DynamicImage::ImageLumaA8(rgb.to_luma_alpha8()),
                    ImageFormat::Png,
                ),
            },
            Seed {
                name: "photo.jpg".into(),
                bytes: encoded(rgb.clone(), ImageFormat::Jpeg),
            },
            Seed {
                name: "frame.gif".into(),
                bytes: encoded(DynamicImage::ImageRgba8(rgb.to_rgba8()), ImageFormat::Gif),
            },
        ]
    })
}

/// How the tests read this format.
const FORMAT: FileFormat = FileFormat {
    name: "images",
    read: |p| read(p),
    bound: |_| BOUND,
};

fixed_tests!(FORMAT, seeds());

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_images(
        seed in 0..seeds().len(),
        edits in mutate::mutations(),
        checksums in any::<bool>(),
    ) {
        let s = &seeds()[seed];
        let mut bytes = mutate::apply(&s.bytes, &edits);
        if checksums && s.name.ends_with(".png") {
            mutate::fix_png_checksums(&mut bytes);
        }
        FORMAT.case(&s.name, &bytes)?;
    }
}
