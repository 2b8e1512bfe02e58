//! Per-axis quality of a synthesized cube: each axis's mid slice scored against that axis's
//! exemplar by every figure of `quality/` and the energy, so `solid` and `bench solid` report
//! the same numbers for the same volume.

use super::roles::SolidExemplars;
use super::slices::slice;
use super::volume::SolidSynthesis;
use crate::quality::{ExemplarFigures, VolumeAnisotropy, VolumeDiagonal};
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
}

/// One exemplar's calibrated figures, computed once and applied to every image scored
/// against it.
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
        })
    }
}

/// One [`ImageScorer`] per role of `exemplars`.
pub fn role_scorers(exemplars: &SolidExemplars) -> [ImageScorer; 3] {
    std::array::from_fn(|r| ImageScorer::new(exemplars.role(r)))
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
        out.push(q);
    }
    Ok(out.try_into().expect("three axes"))
}
