//! Image output errors: each names the file (or the film layer) and what failed, with numbers.
//!
//! The underlying error is part of the message and deliberately not exposed as `source()`:
//! reporters that print the whole chain (`anyhow`'s `{:#}`) would otherwise repeat it.

use std::path::PathBuf;

/// Why a film could not be built, written or read back.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A film must have at least one pixel: neither EXR nor PNG can store an empty image.
    #[error("film size {width}x{height}: width and height must both be at least 1")]
    EmptyFilm {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// The pixel count does not fit in memory indexing (`width * height` overflows `usize`).
    #[error("film size {width}x{height}: too many pixels to address")]
    FilmTooLarge {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// A layer's length does not match `width * height`.
    #[error(
        "film {layer} layer has {actual} pixels, but a {width}x{height} film needs {expected}"
    )]
    LayerLength {
        /// `color`, `albedo`, `normal` or `depth`.
        layer: &'static str,
        /// Film width.
        width: u32,
        /// Film height.
        height: u32,
        /// `width * height`.
        expected: usize,
        /// The length that was given.
        actual: usize,
    },
    /// A file-system operation failed.
    #[error("{file}: cannot {action}: {cause}")]
    Io {
        /// The file being written or read (for a temporary file: the final name).
        file: PathBuf,
        /// What was being done, e.g. `create a temporary file in /out`.
        action: String,
        /// The I/O error.
        cause: std::io::Error,
    },
    /// The OpenEXR encoder or decoder failed.
    #[error("{file}: OpenEXR: {cause}")]
    Exr {
        /// The file.
        file: PathBuf,
        /// The exr crate's error.
        cause: exr::error::Error,
    },
    /// The PNG (or GIF) encoder failed.
    #[error("{file}: image encoding: {cause}")]
    Png {
        /// The file.
        file: PathBuf,
        /// The image crate's error.
        cause: image::ImageError,
    },
    /// An EXR file has no image this renderer can read.
    #[error("{file}: no layer has all of the channels {wanted} (channels found: {found})")]
    MissingRgb {
        /// The file.
        file: PathBuf,
        /// The three channels looked for, comma-separated.
        wanted: String,
        /// Every channel the file has, comma-separated.
        found: String,
    },
    /// A pixel that no 8-bit image can show: a NaN would silently become black.
    #[error(
        "{file}: pixel ({x}, {y}) of the {layer} layer is {value}; an 8-bit PNG cannot show it \
         (write an EXR to keep it)"
    )]
    NotDisplayable {
        /// The file.
        file: PathBuf,
        /// Which layer.
        layer: &'static str,
        /// Column, 0 at the left.
        x: u32,
        /// Row, 0 at the top.
        y: u32,
        /// The offending value, as text.
        value: String,
    },
}

impl From<lazysolid_compute::atomic_file::AtomicWriteError> for OutputError {
    fn from(e: lazysolid_compute::atomic_file::AtomicWriteError) -> OutputError {
        OutputError::Io {
            file: e.path,
            action: e.action,
            cause: e.cause,
        }
    }
}
