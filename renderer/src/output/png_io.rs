//! 8-bit sRGB PNG output: the image for people (and for FLIP, which expects sRGB), and quick
//! looks at the auxiliary layers while debugging.

use super::tonemap::encode8;
use super::{write_atomically, Film, OutputError, ToneMap};
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};
use std::path::Path;

/// How an auxiliary layer's values become display values in [`write_layer_png`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerMapping {
    /// Linear values in 0..1 (albedo or any reflectance): clamped, then the sRGB OETF, so the
    /// PNG looks like the colour the layer stands for.
    Albedo,
    /// Components in -1..1 (unit normals): `(x + 1) / 2`, clamped, stored without the sRGB
    /// curve, the usual normal-map convention (+X red, +Y green, +Z blue; 128 is zero).
    Normal,
}

impl LayerMapping {
    fn name(self) -> &'static str {
        match self {
            LayerMapping::Albedo => "albedo",
            LayerMapping::Normal => "normal",
        }
    }

    fn encode(self, p: [f32; 3]) -> [u8; 3] {
        match self {
            LayerMapping::Albedo => p.map(encode8),
            LayerMapping::Normal => {
                p.map(|x| ((x * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8)
            }
        }
    }
}

/// Encodes an RGB8 buffer as PNG through a temporary file.
pub(crate) fn write_rgb8(
    path: &Path,
    width: u32,
    height: u32,
    data: &[u8],
) -> Result<(), OutputError> {
    write_atomically(path, |writer| {
        PngEncoder::new(writer)
            .write_image(data, width, height, ExtendedColorType::Rgb8)
            .map_err(|cause| OutputError::Png {
                file: path.to_path_buf(),
                cause,
            })
    })
}

/// Encodes `layer` pixel by pixel, refusing the first pixel `encode` cannot show.
pub(super) fn encode_pixels(
    path: &Path,
    layer_name: &'static str,
    width: u32,
    layer: &[[f32; 3]],
    encode: impl Fn([f32; 3]) -> Option<[u8; 3]>,
) -> Result<Vec<u8>, OutputError> {
    let mut data = Vec::with_capacity(layer.len() * 3);
    for (i, &p) in layer.iter().enumerate() {
        let Some(code) = encode(p) else {
            return Err(OutputError::NotDisplayable {
                file: path.to_path_buf(),
                layer: layer_name,
                x: (i % width as usize) as u32,
                y: (i / width as usize) as u32,
                value: format!("{p:?}"),
            });
        };
        data.extend_from_slice(&code);
    }
    Ok(data)
}

/// Writes the film's colour layer as an 8-bit sRGB PNG through `tone_map` (exposure, curve,
/// sRGB OETF, rounding to nearest).
///
/// # Errors
/// A NaN in the colour layer (named with its pixel: it would silently turn black), a missing
/// or unwritable folder, or an encoder failure. Nothing is left at `path` on error.
pub fn write_png(
    film: &Film,
    path: impl AsRef<Path>,
    tone_map: &ToneMap,
) -> Result<(), OutputError> {
    let path = path.as_ref();
    let data = encode_pixels(path, "color", film.width(), film.color(), |c| {
        tone_map.to_srgb8(c)
    })?;
    write_rgb8(path, film.width(), film.height(), &data)
}

/// The film's colour layer as the 8-bit sRGB image [`write_png`] would write, in memory: what
/// FLIP comparisons of renders take.
///
/// # Errors
/// A NaN in the colour layer, named with its pixel (the file is `<in memory>`).
pub fn tonemapped_rgb8(film: &Film, tone_map: &ToneMap) -> Result<image::RgbImage, OutputError> {
    let data = encode_pixels(
        Path::new("<in memory>"),
        "color",
        film.width(),
        film.color(),
        |c| tone_map.to_srgb8(c),
    )?;
    Ok(image::RgbImage::from_raw(film.width(), film.height(), data)
        .expect("a film's layer has width × height pixels"))
}

/// Writes a three-component layer (a film's albedo or normal, or any buffer of that shape) as
/// an 8-bit PNG, for looking at what the integrator saw at the first hit.
///
/// # Errors
/// `layer.len()` other than `width * height` (or a zero size), a NaN component, a missing or
/// unwritable folder, or an encoder failure. Nothing is left at `path` on error.
pub fn write_layer_png(
    layer: &[[f32; 3]],
    width: u32,
    height: u32,
    mapping: LayerMapping,
    path: impl AsRef<Path>,
) -> Result<(), OutputError> {
    let path = path.as_ref();
    let expected = (width as usize).checked_mul(height as usize);
    if width == 0 || height == 0 {
        return Err(OutputError::EmptyFilm { width, height });
    }
    let Some(expected) = expected else {
        return Err(OutputError::FilmTooLarge { width, height });
    };
    if layer.len() != expected {
        return Err(OutputError::LayerLength {
            layer: mapping.name(),
            width,
            height,
            expected,
            actual: layer.len(),
        });
    }
    let data = encode_pixels(path, mapping.name(), width, layer, |p| {
        (!p.iter().any(|x| x.is_nan())).then(|| mapping.encode(p))
    })?;
    write_rgb8(path, width, height, &data)
}
