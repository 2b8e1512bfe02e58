//! The result of a FLIP comparison: summary statistics and the error map.

use super::DiffError;
use image::RgbImage;
use std::path::Path;

/// Summary of a FLIP comparison. Errors are per pixel in 0..1 (0: indistinguishable); the mean
/// is the single number FLIP's authors recommend, the percentiles show whether the error is
/// spread out (noise) or concentrated (a few wrong pixels).
#[derive(Clone, Debug)]
pub struct FlipReport {
    /// Width of both images.
    pub width: u32,
    /// Height of both images.
    pub height: u32,
    /// Mean per-pixel error.
    pub mean: f32,
    /// Median per-pixel error (nearest rank, unweighted).
    pub median: f32,
    /// 95th percentile per-pixel error (nearest rank).
    pub p95: f32,
    /// 99th percentile per-pixel error (nearest rank).
    pub p99: f32,
    /// Largest per-pixel error.
    pub max: f32,
    /// The per-pixel error through the magma colour map (black: none, pale yellow: 1).
    pub error_map: RgbImage,
}

/// The nearest-rank percentile `p` (0..1) of sorted values: the smallest value with at least
/// `p * n` values at or below it.
fn percentile(sorted: &[f32], p: f64) -> f32 {
    let rank = (p * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

impl FlipReport {
    /// Statistics of a non-empty per-pixel error image.
    pub(crate) fn from_errors(
        width: u32,
        height: u32,
        mut errors: Vec<f32>,
        error_map: RgbImage,
    ) -> FlipReport {
        let mean = (errors.iter().map(|&e| f64::from(e)).sum::<f64>() / errors.len() as f64) as f32;
        errors.sort_unstable_by(f32::total_cmp);
        FlipReport {
            width,
            height,
            mean,
            median: percentile(&errors, 0.5),
            p95: percentile(&errors, 0.95),
            p99: percentile(&errors, 0.99),
            max: errors[errors.len() - 1],
            error_map,
        }
    }

    /// Writes the colour-mapped error image as PNG, through a temporary file and a rename.
    ///
    /// # Errors
    /// A missing or unwritable folder, or an encoder failure; the error names `path`.
    pub fn write_error_map(&self, path: impl AsRef<Path>) -> Result<(), DiffError> {
        crate::output::write_rgb8(
            path.as_ref(),
            self.width,
            self.height,
            self.error_map.as_raw(),
        )?;
        Ok(())
    }
}
