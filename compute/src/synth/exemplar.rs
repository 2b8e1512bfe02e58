//! The exemplar: an 8-bit RGB image read from PNG, JPEG or a GIMP `.pat` pattern, checked
//! against the sizes the pyramid and the analysis support.

use super::error::{SynthError, SynthResult};
use super::pat::decode_pattern;
use std::path::{Path, PathBuf};

/// Smallest exemplar side: the pyramid needs at least 5 levels (`floor(log2(16)) + 1`) for
/// jitter at several scales to mean anything.
pub const MIN_EXEMPLAR_SIDE: u32 = 16;

/// Largest exemplar side: the k-coherence analysis is a brute-force search, quadratic in the
/// pixel count (see `coherence.rs`); 256² keeps it to seconds.
pub const MAX_EXEMPLAR_SIDE: u32 = 256;

/// An RGB exemplar. Colours are what the output shows; synthesis itself works on coordinates
/// into this image.
#[derive(Clone, Debug)]
pub struct Exemplar {
    /// Where it came from (file path or a name), for messages.
    pub source: PathBuf,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGB pixels.
    pub rgb: Vec<[u8; 3]>,
}

impl Exemplar {
    /// Reads `path`: `.pat` files with the GIMP pattern decoder, anything else with the
    /// `image` crate (PNG, JPEG). Grey is replicated to RGB and alpha is dropped.
    ///
    /// # Errors
    /// The file cannot be read or decoded, has an unsupported channel count, or its size is
    /// outside [`MIN_EXEMPLAR_SIDE`]..=[`MAX_EXEMPLAR_SIDE`].
    pub fn load(path: &Path) -> SynthResult<Exemplar> {
        let bytes = std::fs::read(path).map_err(|source| SynthError::Io {
            path: path.to_owned(),
            source,
        })?;
        let is_pat = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("pat"));
        if is_pat {
            let pattern = decode_pattern(path, &bytes)?;
            let c = pattern.channels as usize;
            let rgb = pattern
                .pixels
                .chunks_exact(c)
                .map(|p| match c {
                    1 | 2 => [p[0]; 3],
                    _ => [p[0], p[1], p[2]],
                })
                .collect();
            return Self::from_rgb(path, pattern.width, pattern.height, rgb);
        }
        let image = image::load_from_memory(&bytes).map_err(|e| SynthError::Decode {
            path: path.to_owned(),
            reason: e.to_string(),
        })?;
        let channels = image.color().channel_count() as u32;
        if !(1..=4).contains(&channels) {
            return Err(SynthError::Channels {
                path: path.to_owned(),
                channels,
            });
        }
        let rgb8 = image.to_rgb8();
        let (w, h) = rgb8.dimensions();
        let rgb = rgb8.pixels().map(|p| p.0).collect();
        Self::from_rgb(path, w, h, rgb)
    }

    /// Wraps pixels already in memory; `source` names them in messages.
    ///
    /// # Errors
    /// [`SynthError::Size`] when a side is outside the supported range, or
    /// [`SynthError::Parameter`] when `rgb` does not hold `width * height` pixels.
    pub fn from_rgb(
        source: impl Into<PathBuf>,
        width: u32,
        height: u32,
        rgb: Vec<[u8; 3]>,
    ) -> SynthResult<Exemplar> {
        let source = source.into();
        if width.min(height) < MIN_EXEMPLAR_SIDE || width.max(height) > MAX_EXEMPLAR_SIDE {
            return Err(SynthError::Size {
                path: source,
                width,
                height,
                min: MIN_EXEMPLAR_SIDE,
                max: MAX_EXEMPLAR_SIDE,
            });
        }
        if rgb.len() != width as usize * height as usize {
            return Err(SynthError::Parameter {
                name: "exemplar pixels",
                value: rgb.len().to_string(),
                limit: format!("a {width}x{height} exemplar has {} pixels", width * height),
            });
        }
        Ok(Exemplar {
            source,
            width,
            height,
            rgb,
        })
    }

    /// Index `L` of the finest pyramid level: `floor(log2(min(width, height)))`, so that the
    /// coarsest level's spacing `2^L` spans (nearly) the whole exemplar.
    pub fn finest_level(&self) -> u32 {
        self.width.min(self.height).ilog2()
    }

    /// The colour at exemplar coordinate (`x`, `y`).
    pub fn at(&self, x: u32, y: u32) -> [u8; 3] {
        self.rgb[(y * self.width + x) as usize]
    }
}
