//! The exemplar: an 8-bit RGB image in the sizes the pyramid and the analysis support. Images
//! of other sizes become exemplars through `fit.rs`, which says what it did.

use super::decode::DecodedImage;
use super::error::{SynthError, SynthResult};
use std::path::{Path, PathBuf};

/// Smallest exemplar side: the pyramid needs at least 5 levels (`floor(log2(16)) + 1`) for
/// jitter at several scales to mean anything.
pub const MIN_EXEMPLAR_SIDE: u32 = 16;

/// Largest exemplar side: the k-coherence analysis compares every pixel with a pool of at
/// most 4096 (see `coherence.rs`), so it grows with the pixel count; at 512² it took 45 s on
/// two cores shared with other work, 8 s at 256² (docs/synthesis.md). Larger images are
/// resampled to this by `fit.rs`.
pub const MAX_EXEMPLAR_SIDE: u32 = 512;

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
    /// Reads `path` as it is (`DecodedImage::read`: PNG, JPEG or GIMP pattern; grey replicated
    /// to RGB, alpha dropped), without fitting it: for images known to be in range, such as
    /// the asset patterns. Commands that take any image use `fit::load_plane` or
    /// `fit::load_solid` instead.
    ///
    /// # Errors
    /// The file cannot be read or decoded, has an unsupported channel count, or its size is
    /// outside [`MIN_EXEMPLAR_SIDE`]..=[`MAX_EXEMPLAR_SIDE`].
    pub fn load(path: &Path) -> SynthResult<Exemplar> {
        let image = DecodedImage::read(path)?;
        Self::from_rgb(path, image.width, image.height, image.rgb)
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
