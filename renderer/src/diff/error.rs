//! Image comparison errors: each names the image (its file, when it came from one) and sizes.
//!
//! As for [`OutputError`], the underlying error is in the message, not in `source()`, so that
//! chain-printing reporters do not repeat it.

use crate::output::OutputError;
use std::path::PathBuf;

/// Why two images could not be compared, or the error map not written.
#[derive(Debug, thiserror::Error)]
pub enum DiffError {
    /// The file could not be opened or its format sniffed.
    #[error("{file}: cannot open: {cause}")]
    Open {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        cause: std::io::Error,
    },
    /// The file is not an image the decoder understands.
    #[error("{file}: cannot decode the image: {cause}")]
    Decode {
        /// The file.
        file: PathBuf,
        /// The image crate's error.
        cause: image::ImageError,
    },
    /// A floating-point image: FLIP's LDR comparison needs display-referred sRGB, and
    /// quantizing linear HDR values to 8 bits would compare the wrong thing.
    #[error(
        "{file}: a floating-point (HDR) image; FLIP compares 8-bit sRGB images, so tone-map it \
         to PNG first"
    )]
    HighDynamicRange {
        /// The file.
        file: PathBuf,
    },
    /// An image with no pixels.
    #[error("{image} is {width}x{height}; it has no pixels to compare")]
    Empty {
        /// The file, or which in-memory image.
        image: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
    },
    /// Too many pixels for FLIP's 32-bit byte count.
    #[error("{image} is {width}x{height}; FLIP handles at most 2^32 / 3 pixels")]
    TooLarge {
        /// The file, or which in-memory image.
        image: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
    },
    /// The images differ in size, so no pixel corresponds to another.
    #[error(
        "{reference} is {}x{} but {test} is {}x{}; FLIP compares images of the same size",
        reference_size.0, reference_size.1, test_size.0, test_size.1
    )]
    SizeMismatch {
        /// The reference file, or `the reference image`.
        reference: String,
        /// Its width and height.
        reference_size: (u32, u32),
        /// The test file, or `the test image`.
        test: String,
        /// Its width and height.
        test_size: (u32, u32),
    },
    /// Writing the error map failed.
    #[error(transparent)]
    Write(#[from] OutputError),
}
