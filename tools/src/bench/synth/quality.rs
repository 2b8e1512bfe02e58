//! Output quality of both synthesizers, scored the same way: the project's 7×7 neighbourhood
//! energy (GPU kernel, same sample positions for both), the colour-histogram distance, the
//! calibrated multi-scale sliced Wasserstein distance and the blockiness (`synth::quality`),
//! all against the exemplar; and a side-by-side image so the numbers can be checked by eye.

use super::super::plot::rgb_image;
use lazysolid_synth::quality::ExemplarFigures;
use lazysolid_synth::{
    histogram_distance, period_repetition, EnergyKernel, EnergyReport, Exemplar,
};
use std::path::Path;

/// Scores of one output image.
#[derive(Clone, Copy, Debug)]
pub struct Quality {
    /// Mean smallest 7×7 neighbourhood distance (sum over 147 values, 8-bit units).
    pub energy: f64,
    /// The same per compared value.
    pub energy_per_value: f64,
    /// Output pixels the energy evaluated.
    pub samples: usize,
    /// Total variation between the joint RGB histograms, in [0, 1].
    pub histogram: f64,
    /// Share of pixel pairs one exemplar period apart that copy (nearly) the same exemplar pixel
    /// (`period_repetition`): the plain tiling scores 1.
    pub repetition: f64,
    /// Multi-scale sliced Wasserstein distance over the exemplar's own (its two halves'): 1 is
    /// the material's variability.
    pub swd_ratio: f64,
    /// Axis share of the gradient energy over the exemplar's: above 1, blocks.
    pub blockiness: f64,
    /// Correlation of the large structures one exemplar period apart
    /// (`quality::layout_repetition`): 1 for a tiling, even one whose detail was re-synthesized.
    pub layout: f64,
}

/// Scores a `size`² image (and its coordinate map) against `exemplar` with at most `samples`
/// energy positions.
pub fn measure(
    kernel: &EnergyKernel,
    figures: &ExemplarFigures,
    exemplar: &Exemplar,
    image: &[[u8; 3]],
    coords: &[u32],
    size: u32,
    samples: usize,
) -> anyhow::Result<Quality> {
    let minima = kernel.minima(exemplar, image, size, size, samples)?;
    let report = EnergyReport::from_minima(&minima);
    let f = figures.measure(image, size, size);
    Ok(Quality {
        swd_ratio: f.swd.ratio,
        blockiness: f.blockiness.ratio,
        layout: f.layout,
        energy: report.mean,
        energy_per_value: report.per_value,
        samples: report.samples,
        histogram: histogram_distance(&exemplar.rgb, image),
        repetition: period_repetition(coords, size, size, exemplar.width, exemplar.height),
    })
}

/// Scores of one synthesizer over several seeds: single-seed energies move by ±25 % with the
/// seed (the layout the jitter picks), so the comparison is made on the mean.
#[derive(Clone, Debug)]
pub struct SeedScores {
    /// One score per seed, in seed order.
    pub per_seed: Vec<Quality>,
}

impl SeedScores {
    fn mean(&self, f: impl Fn(&Quality) -> f64) -> f64 {
        self.per_seed.iter().map(f).sum::<f64>() / self.per_seed.len().max(1) as f64
    }

    /// Mean energy over the seeds.
    pub fn energy(&self) -> f64 {
        self.mean(|q| q.energy)
    }

    /// Mean energy per compared value.
    pub fn energy_per_value(&self) -> f64 {
        self.mean(|q| q.energy_per_value)
    }

    /// Smallest and largest single-seed energy.
    pub fn energy_range(&self) -> (f64, f64) {
        self.per_seed
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
                (lo.min(q.energy), hi.max(q.energy))
            })
    }

    /// Mean period repetition.
    pub fn repetition(&self) -> f64 {
        self.mean(|q| q.repetition)
    }

    /// Mean SWD ratio.
    pub fn swd_ratio(&self) -> f64 {
        self.mean(|q| q.swd_ratio)
    }

    /// Mean layout repetition.
    pub fn layout(&self) -> f64 {
        self.mean(|q| q.layout)
    }

    /// Mean blockiness.
    pub fn blockiness(&self) -> f64 {
        self.mean(|q| q.blockiness)
    }

    /// Mean histogram distance.
    pub fn histogram(&self) -> f64 {
        self.mean(|q| q.histogram)
    }

    /// Energy positions per image (the same for every seed).
    pub fn samples(&self) -> usize {
        self.per_seed.first().map_or(0, |q| q.samples)
    }
}

/// Pixels of white between the two images.
const GAP: u32 = 8;

/// Writes `left | gap | right`, two `size`² images, as one PNG.
pub fn side_by_side(
    path: &Path,
    left: &[[u8; 3]],
    right: &[[u8; 3]],
    size: u32,
) -> anyhow::Result<()> {
    let width = 2 * size + GAP;
    let s = size as usize;
    let mut pixels = Vec::with_capacity(width as usize * s * 3);
    for y in 0..s {
        pixels.extend(left[y * s..(y + 1) * s].iter().flatten());
        pixels.extend(std::iter::repeat_n(255u8, GAP as usize * 3));
        pixels.extend(right[y * s..(y + 1) * s].iter().flatten());
    }
    rgb_image(path, width, size, pixels)
}
