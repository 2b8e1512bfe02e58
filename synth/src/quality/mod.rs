//! Figures of how much a synthesized image (a 2D output or a slice of a volume) looks like its
//! exemplar, made to be read side by side because each one alone can be gamed: a near-copy has
//! a low neighbourhood energy, blocks have no repetition, a blur keeps the colour histogram.
//!
//! - [`swd`]: a multi-scale sliced Wasserstein distance between the 7×7 patch distributions of
//!   the image and of the exemplar on three octaves of a Gaussian pyramid, calibrated by the
//!   same distance between two disjoint halves of the exemplar (the material's own
//!   variability): the ratio is 1 for an output as close to the exemplar as the exemplar is to
//!   itself, and large structures count through the coarse octaves.
//! - [`anisotropy`](mod@anisotropy): the balance of gradient energy between the image axes, and the identity
//!   that keeps a volume from giving all three slice families one exemplar's balance.
//! - [`band_contrast`](mod@band_contrast): each pyramid band's contrast over the exemplar's, the direction
//!   (smoother or grainier) that the SWD's per-band ratio does not say.
//! - [`blockiness`]: the share of oriented gradient energy that lies along the image axes,
//!   against the exemplar's: axis-aligned blocks raise it, a blur or a shift leave it.
//! - [`layout`]: the correlation of the image's large structures with themselves one
//!   exemplar period away: a grid of the exemplar's copies shows even where the fine detail
//!   was re-synthesized.
//!
//! See `docs/synthesis.md`, "Quality figures".

pub mod anisotropy;
pub mod band_contrast;
pub mod blockiness;
pub mod diagonal;
mod gradient_moments;
mod image;
pub mod layout;
pub mod swd;

pub use anisotropy::{anisotropy, reachable_gap, VolumeAnisotropy};
pub use band_contrast::{band_contrast, band_deviations};
pub use blockiness::{axis_share, Blockiness};
pub use diagonal::{diagonal_correlation, VolumeDiagonal};
pub use image::LinearImage;
pub use layout::layout_repetition;
pub use swd::{PatchSets, SwdCalibration, SwdParams, SwdReport, SWD_BANDS};

/// The figures of one image against an exemplar.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ImageFigures {
    /// Sliced Wasserstein distance of the patch distributions, calibrated.
    pub swd: SwdReport,
    /// Axis share against the exemplar's.
    pub blockiness: Blockiness,
    /// Balance of the gradient energy between u and v ([`anisotropy()`](fn@anisotropy)).
    pub anisotropy: f64,
    /// Which diagonal the gradients prefer ([`diagonal_correlation`]).
    pub diagonal: f64,
    /// Correlation of the large structures one exemplar period away
    /// ([`layout_repetition`]): 1 for a tiling.
    pub layout: f64,
    /// Each band's contrast over the exemplar's, finest first ([`band_contrast()`](fn@band_contrast)).
    pub band_contrast: [f64; SWD_BANDS],
}

/// An exemplar's calibration for every figure, made once and applied to each image scored
/// against it.
#[derive(Clone, Debug)]
pub struct ExemplarFigures {
    swd: SwdCalibration,
    axis_share: f64,
    anisotropy: f64,
    diagonal: f64,
    band_deviations: [f64; SWD_BANDS],
    period: [usize; 2],
}

impl ExemplarFigures {
    /// Calibrates on an 8-bit RGB exemplar of `width`×`height`.
    pub fn new(rgb: &[[u8; 3]], width: u32, height: u32) -> ExemplarFigures {
        let e = LinearImage::from_rgb8(rgb, width as usize, height as usize);
        ExemplarFigures {
            swd: SwdCalibration::new(&e, SwdParams::default()),
            axis_share: axis_share(&e),
            anisotropy: anisotropy(&e),
            diagonal: diagonal_correlation(&e),
            band_deviations: band_deviations(&e),
            period: [width as usize, height as usize],
        }
    }

    /// The exemplar's [`anisotropy()`](fn@anisotropy).
    pub fn anisotropy(&self) -> f64 {
        self.anisotropy
    }

    /// The exemplar's [`diagonal_correlation`].
    pub fn diagonal(&self) -> f64 {
        self.diagonal
    }

    /// The SWD calibration.
    pub fn swd(&self) -> &SwdCalibration {
        &self.swd
    }

    /// Scores an 8-bit RGB image of `width`×`height`.
    pub fn measure(&self, rgb: &[[u8; 3]], width: u32, height: u32) -> ImageFigures {
        let image = LinearImage::from_rgb8(rgb, width as usize, height as usize);
        ImageFigures {
            swd: self.swd.measure(&image),
            blockiness: Blockiness::against(&image, self.axis_share),
            anisotropy: anisotropy(&image),
            diagonal: diagonal_correlation(&image),
            layout: layout_repetition(&image, self.period[0], self.period[1]),
            band_contrast: band_contrast(&image, &self.band_deviations),
        }
    }
}
