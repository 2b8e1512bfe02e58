//! Per-axis quality of a synthesized cube: each axis's mid slice scored against that axis's
//! exemplar by every figure of `quality/` and the energy, so `solid` and `bench solid` report
//! the same numbers for the same volume.

use super::roles::SolidExemplars;
use super::slices::slice;
use super::volume::SolidSynthesis;
use crate::quality::{ExemplarFigures, ImageFigures, VolumeAnisotropy, VolumeDiagonal, SWD_BANDS};
use crate::{
    histogram_distance, period_repetition, EnergyKernel, EnergyReport, Exemplar, SynthResult,
};

/// Quality of the slices perpendicular to one axis.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct AxisQuality {
    /// Mean 7×7 neighbourhood energy of the mid slice against the axis's exemplar.
    pub energy: f64,
    /// Colour-histogram distance of the mid slice to the exemplar.
    pub histogram: f64,
    /// Period repetition of the role's coordinates in the mid slice.
    pub repetition: f64,
    /// Multi-scale sliced Wasserstein distance of the mid slice's patches to the exemplar's
    /// (8-bit levels, mean over octaves).
    pub swd: f64,
    /// `swd` over the distance between the exemplar's two halves: 1 is the material's own
    /// variability.
    pub swd_ratio: f64,
    /// Share of oriented gradient energy along the image axes over the exemplar's: 1 is as
    /// axis-aligned as the material, above it blocks.
    pub blockiness: f64,
    /// `(J_uu − J_vv) / (J_uu + J_vv)` of the gradient energy over all of this axis's
    /// slices (`synth/quality/anisotropy.rs`).
    pub anisotropy: f64,
    /// The same figure of the axis's exemplar: no volume matches it on every axis unless
    /// `a_x − a_y + a_z = 0`.
    pub exemplar_anisotropy: f64,
    /// `J_uv / √(J_uu J_vv)` of the gradients over all of this axis's slices: which
    /// diagonal the structures prefer (`synth/quality/diagonal.rs`).
    pub diagonal: f64,
    /// The same figure of the axis's exemplar: a negative one cannot be met on all three axes
    /// with the same sign in every role (`solid/orientation.rs`).
    pub exemplar_diagonal: f64,
    /// Mean of `swd_ratio` over [`QUALITY_SLICES`] evenly spaced slices perpendicular to the
    /// axis (for a 2D synthesis, its own, or the bench's mean over eight seeds): at 128³ the mid slice alone moves by up to ±0.3
    /// between seeds and between slices of one volume, the mean of eight by at most 0.11
    /// (granite1, seeds 3 and 5, both orientations).
    pub slices_swd_ratio: f64,
    /// Standard deviation of `swd_ratio` over those slices (0 for one image).
    pub slices_swd_ratio_sd: f64,
    /// Mean of `blockiness` over those slices.
    pub slices_blockiness: f64,
    /// Mean over those slices of each SWD band's ratio, finest first (`SwdReport::bands`):
    /// the finest band is the one- and two-pixel detail the finest level makes, the coarsest
    /// the layout the coarse levels make.
    pub slices_swd_bands: [f64; SWD_BANDS],
    /// Mean over those slices of each band's contrast over the exemplar's, finest first
    /// (`quality::band_contrast`): below 1 smoother than the material at that scale, above 1
    /// grainier; the direction the band's SWD ratio does not give.
    pub slices_band_contrast: [f64; SWD_BANDS],
}

/// The figures of one slice (or one 2D synthesis) that [`AxisQuality::set_means`] averages.
#[derive(Clone, Copy, Debug)]
pub struct SliceRatios {
    /// SWD ratio, mean over the bands.
    pub swd: f64,
    /// Blockiness ratio.
    pub blockiness: f64,
    /// SWD ratio per band, finest first.
    pub bands: [f64; SWD_BANDS],
    /// Contrast per band over the exemplar's, finest first.
    pub contrast: [f64; SWD_BANDS],
}

impl SliceRatios {
    fn of(f: &ImageFigures) -> SliceRatios {
        SliceRatios {
            swd: f.swd.ratio,
            blockiness: f.blockiness.ratio,
            bands: f.swd.bands(),
            contrast: f.band_contrast,
        }
    }
}

impl AxisQuality {
    /// The scored image's own [`SliceRatios`], as [`ImageScorer::score`] left them: the
    /// first of the figures a caller averages with [`AxisQuality::set_means`].
    pub fn own_ratios(&self) -> SliceRatios {
        SliceRatios {
            swd: self.swd_ratio,
            blockiness: self.blockiness,
            bands: self.slices_swd_bands,
            contrast: self.slices_band_contrast,
        }
    }

    /// Sets the `slices_*` means from several images' figures.
    pub fn set_means(&mut self, figures: &[SliceRatios]) {
        let count = figures.len().max(1) as f64;
        let mean = figures.iter().map(|f| f.swd).sum::<f64>() / count;
        self.slices_swd_ratio = mean;
        self.slices_swd_ratio_sd =
            (figures.iter().map(|f| (f.swd - mean).powi(2)).sum::<f64>() / count).sqrt();
        self.slices_blockiness = figures.iter().map(|f| f.blockiness).sum::<f64>() / count;
        self.slices_swd_bands =
            std::array::from_fn(|b| figures.iter().map(|f| f.bands[b]).sum::<f64>() / count);
        self.slices_band_contrast =
            std::array::from_fn(|b| figures.iter().map(|f| f.contrast[b]).sum::<f64>() / count);
    }
}

/// Slices per axis whose figures are averaged: at `(2k + 1) n / 16`, k = 0..8.
pub const QUALITY_SLICES: u32 = 8;

/// One exemplar's calibrated figures, computed once and applied to every image scored
/// against it.
#[derive(Clone)]
pub struct ImageScorer(ExemplarFigures);

impl ImageScorer {
    /// Calibrates on `exemplar`.
    pub fn new(exemplar: &Exemplar) -> ImageScorer {
        ImageScorer(ExemplarFigures::new(
            &exemplar.rgb,
            exemplar.width,
            exemplar.height,
        ))
    }

    /// The SWD ratios and blockiness of a `w`×`h` image alone: what a mean over several
    /// images or slices needs, without the energy.
    pub fn ratios(&self, rgb: &[[u8; 3]], w: u32, h: u32) -> SliceRatios {
        SliceRatios::of(&self.0.measure(rgb, w, h))
    }

    /// Scores a `w`×`h` image: energy (GPU), histogram, the given repetition, SWD and
    /// blockiness.
    #[allow(clippy::too_many_arguments)]
    pub fn score(
        &self,
        energy: &EnergyKernel,
        exemplar: &Exemplar,
        rgb: &[[u8; 3]],
        w: u32,
        h: u32,
        repetition: f64,
        samples: usize,
    ) -> SynthResult<AxisQuality> {
        let minima = energy.minima(exemplar, rgb, w, h, samples)?;
        let figures = self.0.measure(rgb, w, h);
        Ok(AxisQuality {
            energy: EnergyReport::from_minima(&minima).mean,
            histogram: histogram_distance(&exemplar.rgb, rgb),
            repetition,
            swd: figures.swd.mean,
            swd_ratio: figures.swd.ratio,
            blockiness: figures.blockiness.ratio,
            anisotropy: figures.anisotropy,
            exemplar_anisotropy: self.0.anisotropy(),
            diagonal: figures.diagonal,
            exemplar_diagonal: self.0.diagonal(),
            slices_swd_ratio: figures.swd.ratio,
            slices_swd_ratio_sd: 0.0,
            slices_blockiness: figures.blockiness.ratio,
            slices_swd_bands: figures.swd.bands(),
            slices_band_contrast: figures.band_contrast,
        })
    }
}

/// One [`ImageScorer`] per role of `exemplars`.
pub fn role_scorers(exemplars: &SolidExemplars) -> [ImageScorer; 3] {
    // One calibration per distinct image: roles that share an image share its scorer.
    let per_image: Vec<ImageScorer> = exemplars.images.iter().map(ImageScorer::new).collect();
    std::array::from_fn(|r| per_image[exemplars.role_image[r]].clone())
}

/// Scores the mid slices of a cube perpendicular to each axis against that axis's exemplar.
pub fn axis_quality(
    energy: &EnergyKernel,
    scorers: &[ImageScorer; 3],
    exemplars: &SolidExemplars,
    synthesis: &SolidSynthesis,
    colours: &[[u8; 3]],
    samples: usize,
) -> SynthResult<[AxisQuality; 3]> {
    let n = synthesis.window.size[0];
    let m = exemplars.side();
    let volume = VolumeAnisotropy::measure(colours, n as usize);
    let diagonal = VolumeDiagonal::measure(colours, n as usize);
    let mut out = Vec::with_capacity(3);
    for (axis, scorer) in scorers.iter().enumerate() {
        let (rgb, coords) = slice(synthesis, colours, axis, n / 2);
        let e = exemplars.role(axis);
        let repetition = period_repetition(&coords, n, n, m, m);
        let mut q = scorer.score(energy, e, &rgb, n, n, repetition, samples)?;
        // The mid slice alone is one sample; the identity holds for the families.
        q.anisotropy = volume.axes[axis];
        q.diagonal = diagonal.axes[axis];
        q.set_means(&slice_ratios(scorer, synthesis, colours, axis));
        out.push(q);
    }
    Ok(out.try_into().expect("three axes"))
}

/// The figures of the [`QUALITY_SLICES`] evenly spaced slices perpendicular to `axis` that
/// [`axis_quality`] averages: a caller that scores several volumes of one exemplar (other
/// seeds) pools them before [`AxisQuality::set_means`].
pub fn slice_ratios(
    scorer: &ImageScorer,
    synthesis: &SolidSynthesis,
    colours: &[[u8; 3]],
    axis: usize,
) -> Vec<SliceRatios> {
    let n = synthesis.window.size[0];
    (0..QUALITY_SLICES)
        .map(|k| {
            let at = n * (2 * k + 1) / (2 * QUALITY_SLICES);
            let (rgb, _) = slice(synthesis, colours, axis, at);
            scorer.ratios(&rgb, n, n)
        })
        .collect()
}
