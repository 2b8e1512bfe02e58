//! The animated preview of a rendered sequence: a looping GIF any browser plays, next to the
//! numbered PNG (and EXR) frames that keep the full quality.

use super::png_io::encode_pixels;
use super::{write_atomically, Film, OutputError, ToneMap};
use image::codecs::gif::{GifEncoder, Repeat};
use image::{Delay, Frame, RgbaImage};
use std::path::Path;

/// One frame of the preview `path`: the film tone-mapped like its PNG, as RGBA8.
///
/// # Errors
/// A pixel no 8-bit image can show (NaN), named with the file and its position.
pub fn preview_frame(
    film: &Film,
    path: &Path,
    tone_map: &ToneMap,
) -> Result<RgbaImage, OutputError> {
    let rgb = encode_pixels(path, "color", film.width(), film.color(), |c| {
        tone_map.to_srgb8(c)
    })?;
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    Ok(RgbaImage::from_raw(film.width(), film.height(), rgba).expect("one RGBA word per pixel"))
}

/// Writes `frames` as a looping GIF at `fps` frames per second (GIF delays are whole
/// centiseconds, so the rate is rounded to one of them), through a temporary file.
///
/// # Errors
/// Frames of different sizes, or the file cannot be encoded or written.
pub fn write_gif(path: &Path, frames: &[RgbaImage], fps: f32) -> Result<(), OutputError> {
    let (width, height) = frames.first().map_or((0, 0), |f| f.dimensions());
    if let Some(f) = frames.iter().find(|f| f.dimensions() != (width, height)) {
        return Err(OutputError::LayerLength {
            layer: "color",
            width,
            height,
            expected: width as usize * height as usize,
            actual: f.width() as usize * f.height() as usize,
        });
    }
    let centis = (100.0 / fps).round().max(1.0) as u32;
    write_atomically(path, |w| {
        let encode = |cause: image::ImageError| OutputError::Png {
            file: path.to_path_buf(),
            cause,
        };
        let mut encoder = GifEncoder::new_with_speed(w, 10);
        encoder.set_repeat(Repeat::Infinite).map_err(encode)?;
        for f in frames {
            let delay = Delay::from_numer_denom_ms(centis * 10, 1);
            encoder
                .encode_frame(Frame::from_parts(f.clone(), 0, 0, delay))
                .map_err(encode)?;
        }
        Ok(())
    })
}
