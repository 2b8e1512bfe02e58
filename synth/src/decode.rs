//! Reading an image file into 8-bit RGB, whatever its size and channels: PNG and JPEG through
//! the `image` crate, GIMP `.pat` patterns through `pat.rs`. Nothing here judges whether the
//! image suits a synthesizer; `fit.rs` turns it into an exemplar and says how.

use super::error::{SynthError, SynthResult};
use super::pat::decode_pattern;
use std::fmt;
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Largest side of an image that is decoded at all: a 8192² RGB image is 192 MiB in memory,
/// and any synthesizer resamples it far below that. Checked before the pixels are decoded, so
/// a bogus header cannot make the decoder allocate gigabytes.
pub const MAX_DECODE_SIDE: u32 = 8192;

/// The channels an image had in its file. Synthesis uses RGB only: grey is replicated, alpha
/// is dropped (and the fit's line says so).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChannelLayout {
    /// One grey channel.
    Grey,
    /// Grey and alpha.
    GreyAlpha,
    /// Red, green, blue.
    Rgb,
    /// Red, green, blue and alpha.
    Rgba,
}

impl ChannelLayout {
    /// The layout of `channels` samples per pixel (1 to 4), `None` for any other count.
    pub fn from_channels(channels: u32) -> Option<ChannelLayout> {
        match channels {
            1 => Some(ChannelLayout::Grey),
            2 => Some(ChannelLayout::GreyAlpha),
            3 => Some(ChannelLayout::Rgb),
            4 => Some(ChannelLayout::Rgba),
            _ => None,
        }
    }

    /// Whether the file had an alpha channel (which synthesis drops).
    pub fn has_alpha(self) -> bool {
        matches!(self, ChannelLayout::GreyAlpha | ChannelLayout::Rgba)
    }
}

impl fmt::Display for ChannelLayout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ChannelLayout::Grey => "grey",
            ChannelLayout::GreyAlpha => "grey+alpha",
            ChannelLayout::Rgb => "RGB",
            ChannelLayout::Rgba => "RGBA",
        })
    }
}

/// A decoded image of any size from 1 to [`MAX_DECODE_SIDE`] pixels a side, as RGB.
#[derive(Clone, Debug)]
pub struct DecodedImage {
    /// Where it came from (file path or a name), for messages.
    pub source: PathBuf,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGB pixels (grey replicated, alpha dropped).
    pub rgb: Vec<[u8; 3]>,
    /// The channels the file had.
    pub layout: ChannelLayout,
}

impl DecodedImage {
    /// Reads `path`: `.pat` files with the GIMP pattern decoder, anything else with the
    /// `image` crate (PNG, JPEG, and what else it decodes; 16-bit samples are reduced to 8).
    ///
    /// # Errors
    /// The file cannot be read or decoded, has an unsupported channel count, or a side above
    /// [`MAX_DECODE_SIDE`].
    pub fn read(path: &Path) -> SynthResult<DecodedImage> {
        let bytes = std::fs::read(path).map_err(|source| SynthError::Io {
            path: path.to_owned(),
            source,
        })?;
        let is_pat = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("pat"));
        if is_pat {
            let pattern = decode_pattern(path, &bytes)?;
            let layout =
                ChannelLayout::from_channels(pattern.channels).ok_or(SynthError::Channels {
                    path: path.to_owned(),
                    channels: pattern.channels,
                })?;
            let c = pattern.channels as usize;
            let rgb = pattern
                .pixels
                .chunks_exact(c)
                .map(|p| match c {
                    1 | 2 => [p[0]; 3],
                    _ => [p[0], p[1], p[2]],
                })
                .collect();
            return Self::from_rgb(path, pattern.width, pattern.height, rgb, layout);
        }
        let decode_error = |e: &dyn fmt::Display| SynthError::Decode {
            path: path.to_owned(),
            reason: e.to_string(),
        };
        let reader = || {
            image::ImageReader::new(Cursor::new(&bytes))
                .with_guessed_format()
                .map_err(|e| decode_error(&e))
        };
        let (width, height) = reader()?.into_dimensions().map_err(|e| decode_error(&e))?;
        check_decode_size(path, width, height)?;
        let image = reader()?.decode().map_err(|e| decode_error(&e))?;
        let channels = image.color().channel_count() as u32;
        let layout = ChannelLayout::from_channels(channels).ok_or(SynthError::Channels {
            path: path.to_owned(),
            channels,
        })?;
        let rgb8 = image.to_rgb8();
        let rgb = rgb8.pixels().map(|p| p.0).collect();
        Self::from_rgb(path, width, height, rgb, layout)
    }

    /// Wraps pixels already in memory; `source` names them in messages, `layout` says what
    /// channels they came from.
    ///
    /// # Errors
    /// [`SynthError::Fit`] when a side is 0 or above [`MAX_DECODE_SIDE`], or
    /// [`SynthError::Parameter`] when `rgb` does not hold `width * height` pixels.
    pub fn from_rgb(
        source: impl Into<PathBuf>,
        width: u32,
        height: u32,
        rgb: Vec<[u8; 3]>,
        layout: ChannelLayout,
    ) -> SynthResult<DecodedImage> {
        let source = source.into();
        check_decode_size(&source, width, height)?;
        if rgb.len() != width as usize * height as usize {
            return Err(SynthError::Parameter {
                name: "image pixels",
                value: rgb.len().to_string(),
                limit: format!("a {width}x{height} image has {} pixels", width * height),
            });
        }
        Ok(DecodedImage {
            source,
            width,
            height,
            rgb,
            layout,
        })
    }
}

fn check_decode_size(path: &Path, width: u32, height: u32) -> SynthResult<()> {
    if width == 0 || height == 0 || width.max(height) > MAX_DECODE_SIDE {
        return Err(SynthError::Fit {
            path: path.to_owned(),
            width,
            height,
            limit: format!(
                "images are read up to {MAX_DECODE_SIDE} pixels a side (a larger one would be \
                 resampled far below its resolution anyway; scale it down first)"
            ),
        });
    }
    Ok(())
}
