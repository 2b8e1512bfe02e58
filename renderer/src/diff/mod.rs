//! FLIP image comparison: how different a render looks from a reference, as a person would
//! judge it at a normal viewing distance, rather than a per-pixel error that noise dominates.
//!
//! Uses NVIDIA's FLIP (LDR variant, through the `nv-flip` crate) at its default 67 pixels per
//! degree (a 0.7 m viewing distance from a 24" 4K monitor). Both images are 8-bit sRGB; alpha
//! is dropped.

mod error;
mod report;

pub use error::DiffError;
pub use report::FlipReport;

use image::{DynamicImage, RgbImage};
use std::path::Path;

/// Compares a test image file with a reference image file (PNG or JPEG, alpha dropped,
/// 16-bit scaled to 8-bit).
///
/// # Errors
/// A missing or undecodable file (named), a floating-point image (FLIP's LDR comparison needs
/// display-referred sRGB; tone-map it first), an empty image, or different sizes (both files
/// and sizes named).
pub fn flip_files(reference: &Path, test: &Path) -> Result<FlipReport, DiffError> {
    let r = load(reference)?;
    let t = load(test)?;
    compare(
        &r,
        &reference.display().to_string(),
        &t,
        &test.display().to_string(),
    )
}

/// Compares two images already in memory (sRGB, 8 bits per channel).
///
/// # Errors
/// An empty image, one too large for FLIP's 32-bit indexing, or different sizes.
pub fn flip_images(reference: &RgbImage, test: &RgbImage) -> Result<FlipReport, DiffError> {
    compare(reference, "the reference image", test, "the test image")
}

fn load(path: &Path) -> Result<RgbImage, DiffError> {
    let reader = image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .map_err(|cause| DiffError::Open {
            file: path.to_path_buf(),
            cause,
        })?;
    let image = reader.decode().map_err(|cause| DiffError::Decode {
        file: path.to_path_buf(),
        cause,
    })?;
    if matches!(
        image,
        DynamicImage::ImageRgb32F(_) | DynamicImage::ImageRgba32F(_)
    ) {
        return Err(DiffError::HighDynamicRange {
            file: path.to_path_buf(),
        });
    }
    Ok(image.into_rgb8())
}

fn check_size(image: &RgbImage, name: &str) -> Result<(), DiffError> {
    let (width, height) = image.dimensions();
    if width == 0 || height == 0 {
        return Err(DiffError::Empty {
            image: name.to_string(),
            width,
            height,
        });
    }
    // nv-flip computes `width * height * 3` in u32.
    if width
        .checked_mul(height)
        .and_then(|n| n.checked_mul(3))
        .is_none()
    {
        return Err(DiffError::TooLarge {
            image: name.to_string(),
            width,
            height,
        });
    }
    Ok(())
}

fn compare(
    reference: &RgbImage,
    reference_name: &str,
    test: &RgbImage,
    test_name: &str,
) -> Result<FlipReport, DiffError> {
    check_size(reference, reference_name)?;
    check_size(test, test_name)?;
    if reference.dimensions() != test.dimensions() {
        return Err(DiffError::SizeMismatch {
            reference: reference_name.to_string(),
            reference_size: reference.dimensions(),
            test: test_name.to_string(),
            test_size: test.dimensions(),
        });
    }
    let (width, height) = reference.dimensions();
    let error = nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(width, height, reference.as_raw()),
        nv_flip::FlipImageRgb8::with_data(width, height, test.as_raw()),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let colored = error.apply_color_lut(&nv_flip::magma_lut());
    let error_map = RgbImage::from_raw(width, height, colored.to_vec())
        .expect("nv-flip returns width * height * 3 bytes");
    Ok(FlipReport::from_errors(
        width,
        height,
        error.to_vec(),
        error_map,
    ))
}
