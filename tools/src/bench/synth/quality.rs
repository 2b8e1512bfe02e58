//! Output quality of both synthesizers, scored the same way: the project's 7×7 neighbourhood
//! energy (GPU kernel, same sample positions for both) and the colour-histogram distance, both
//! against the exemplar; and a side-by-side image so the numbers can be checked by eye.

use super::super::plot::rgb_image;
use lazysolid_compute::synth::{histogram_distance, EnergyKernel, EnergyReport, Exemplar};
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
}

/// Scores a `size`² image against `exemplar` with at most `samples` energy positions.
pub fn measure(
    kernel: &EnergyKernel,
    exemplar: &Exemplar,
    image: &[[u8; 3]],
    size: u32,
    samples: usize,
) -> anyhow::Result<Quality> {
    let minima = kernel.minima(exemplar, image, size, size, samples)?;
    let report = EnergyReport::from_minima(&minima);
    Ok(Quality {
        energy: report.mean,
        energy_per_value: report.per_value,
        samples: report.samples,
        histogram: histogram_distance(&exemplar.rgb, image),
    })
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
