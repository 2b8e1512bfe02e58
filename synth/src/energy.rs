//! Quality of a synthesized image. The neighbourhood energy (Kwatra et al. 2005; Eq. 3.1 of
//! Lefebvre's thesis) is the mean, over output pixels, of the smallest squared RGB distance
//! between the pixel's 7×7 neighbourhood and any 7×7 neighbourhood of the (toroidal) exemplar:
//! 0 means every output neighbourhood occurs verbatim in the exemplar. It is computed exactly,
//! by brute force, in integers (GPU kernel `glsl/synth/energy.comp`, CPU reference here); only
//! pixels whose whole neighbourhood lies in the image count, and large images are sampled on a
//! regular subgrid of at most `max_samples` pixels to bound the quadratic cost.
//!
//! The colour-histogram distance complements it: an output can copy exemplar neighbourhoods
//! perfectly yet use only part of the exemplar (e.g. repeat one region); the histogram distance
//! catches that.

use super::error::{SynthError, SynthResult};
use super::exemplar::Exemplar;
use crate::kernels::synth;
use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuBuffer, Kernel};
use std::sync::Arc;

/// Radius of the compared neighbourhoods (7×7).
pub const ENERGY_RADIUS: u32 = 3;

/// Summary of a neighbourhood energy evaluation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnergyReport {
    /// Output pixels evaluated.
    pub samples: usize,
    /// Mean smallest squared distance per neighbourhood (sum over 7·7·3 values, 8-bit units).
    pub mean: f64,
    /// The same per compared value (`mean / 147`): the mean squared error of one channel.
    pub per_value: f64,
}

impl EnergyReport {
    /// Summarizes per-sample minima.
    pub fn from_minima(minima: &[u32]) -> EnergyReport {
        let side = 2 * ENERGY_RADIUS as usize + 1;
        let mean = minima.iter().map(|&m| m as f64).sum::<f64>() / minima.len().max(1) as f64;
        EnergyReport {
            samples: minima.len(),
            mean,
            per_value: mean / (side * side * 3) as f64,
        }
    }
}

/// The output positions evaluated: the interior pixels (neighbourhood inside the image) on the
/// coarsest regular subgrid that has at most `max_samples` of them.
pub fn energy_positions(width: u32, height: u32, max_samples: usize) -> SynthResult<Vec<[u32; 2]>> {
    let side = 2 * ENERGY_RADIUS + 1;
    if width < side || height < side {
        return Err(SynthError::Parameter {
            name: "energy image size",
            value: format!("{width}x{height}"),
            limit: format!(
                "the {side}x{side} neighbourhood energy needs at least {side}x{side} pixels"
            ),
        });
    }
    if max_samples == 0 {
        return Err(SynthError::Parameter {
            name: "energy samples",
            value: "0".into(),
            limit: "must be at least 1".into(),
        });
    }
    let (nx, ny) = (width - 2 * ENERGY_RADIUS, height - 2 * ENERGY_RADIUS);
    let mut stride = 1;
    while nx.div_ceil(stride) as usize * ny.div_ceil(stride) as usize > max_samples {
        stride += 1;
    }
    Ok((0..ny)
        .step_by(stride as usize)
        .flat_map(|y| {
            (0..nx)
                .step_by(stride as usize)
                .map(move |x| [x + ENERGY_RADIUS, y + ENERGY_RADIUS])
        })
        .collect())
}

fn check_image(image: &[[u8; 3]], width: u32, height: u32) -> SynthResult<()> {
    if image.len() != width as usize * height as usize {
        return Err(SynthError::Parameter {
            name: "energy image pixels",
            value: image.len().to_string(),
            limit: format!(
                "a {width}x{height} image has {} pixels",
                width as usize * height as usize
            ),
        });
    }
    Ok(())
}

/// CPU reference: the smallest neighbourhood distance of every position of
/// [`energy_positions`].
///
/// # Errors
/// An image too small for the neighbourhood or whose pixel count does not match its size.
pub fn energy_cpu(
    exemplar: &Exemplar,
    image: &[[u8; 3]],
    width: u32,
    height: u32,
    max_samples: usize,
) -> SynthResult<Vec<u32>> {
    check_image(image, width, height)?;
    let r = ENERGY_RADIUS as i64;
    let (ew, eh) = (exemplar.width as i64, exemplar.height as i64);
    let positions = energy_positions(width, height, max_samples)?;
    Ok(positions
        .iter()
        .map(|&[px, py]| {
            let mut best = u32::MAX;
            for uy in 0..eh {
                for ux in 0..ew {
                    let mut d = 0u32;
                    for dy in -r..=r {
                        for dx in -r..=r {
                            let o =
                                image[((py as i64 + dy) * width as i64 + px as i64 + dx) as usize];
                            let e = exemplar.rgb[((uy + dy).rem_euclid(eh) * ew
                                + (ux + dx).rem_euclid(ew))
                                as usize];
                            for c in 0..3 {
                                let diff = o[c] as i32 - e[c] as i32;
                                d += (diff * diff) as u32;
                            }
                        }
                    }
                    best = best.min(d);
                }
            }
            best
        })
        .collect())
}

lazysolid_compute::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct EnergyPush<'a> {
        exemplar: DeviceAddress<'a>,
        image: DeviceAddress<'a>,
        positions: DeviceAddress<'a>,
        energies: DeviceAddress<'a>,
        exemplar_size: [u32; 2],
        image_width: u32,
        samples: u32,
        first: u32,
        end: u32,
    }
}

/// Exemplar pixels one energy dispatch searches: with the 49-step inner loop this keeps every
/// invocation below llvmpipe's cap of 65535 loop iterations.
const ENERGY_CHUNK: u32 = 1024;

fn pack_rgb(p: &[u8; 3]) -> u32 {
    p[0] as u32 | (p[1] as u32) << 8 | (p[2] as u32) << 16
}

/// The energy kernel, built once.
pub struct EnergyKernel {
    gpu: Gpu,
    kernel: Arc<Kernel>,
}

impl EnergyKernel {
    /// Builds the kernel.
    ///
    /// # Errors
    /// A GPU failure.
    pub fn new(gpu: &Gpu) -> SynthResult<EnergyKernel> {
        Ok(EnergyKernel {
            gpu: gpu.clone(),
            kernel: gpu.kernel(&synth::ENERGY)?,
        })
    }

    /// The GPU equivalent of [`energy_cpu`] (same positions, same integers).
    ///
    /// # Errors
    /// As [`energy_cpu`], or a GPU failure.
    pub fn minima(
        &self,
        exemplar: &Exemplar,
        image: &[[u8; 3]],
        width: u32,
        height: u32,
        max_samples: usize,
    ) -> SynthResult<Vec<u32>> {
        check_image(image, width, height)?;
        let positions: Vec<u32> = energy_positions(width, height, max_samples)?
            .iter()
            .map(|&[x, y]| x | (y << 16))
            .collect();
        let gpu = &self.gpu;
        let ex: Vec<u32> = exemplar.rgb.iter().map(pack_rgb).collect();
        let im: Vec<u32> = image.iter().map(pack_rgb).collect();
        let ex = GpuBuffer::from_slice(gpu, "energy exemplar", &ex)?;
        let im = GpuBuffer::from_slice(gpu, "energy image", &im)?;
        let pos = GpuBuffer::from_slice(gpu, "energy positions", &positions)?;
        let out = GpuBuffer::<u32>::new(gpu, "energy minima", positions.len())?;
        let pixels = exemplar.width * exemplar.height;
        gpu.submit(|rec| {
            for first in (0..pixels).step_by(ENERGY_CHUNK as usize) {
                let push = EnergyPush {
                    exemplar: ex.address(),
                    image: im.address(),
                    positions: pos.address(),
                    energies: out.address(),
                    exemplar_size: [exemplar.width, exemplar.height],
                    image_width: width,
                    samples: positions.len() as u32,
                    first,
                    end: (first + ENERGY_CHUNK).min(pixels),
                };
                let k = &self.kernel;
                rec.dispatch(k, k.groups_for(positions.len() as u64), &[], &push)?;
            }
            Ok(())
        })?;
        Ok(out.read()?)
    }
}

/// Bins per channel of the colour histogram (8 → 512 joint RGB bins).
const HISTOGRAM_BINS: usize = 8;

/// Total-variation distance between the joint RGB histograms of two images (8 bins per
/// channel, each histogram normalized): 0 for the same colour distribution, 1 for disjoint ones.
pub fn histogram_distance(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let histogram = |pixels: &[[u8; 3]]| {
        let mut h = vec![0.0f64; HISTOGRAM_BINS.pow(3)];
        let shift = 8 - HISTOGRAM_BINS.ilog2();
        for p in pixels {
            let [r, g, b] = p.map(|c| (c >> shift) as usize);
            h[(r * HISTOGRAM_BINS + g) * HISTOGRAM_BINS + b] += 1.0 / pixels.len().max(1) as f64;
        }
        h
    };
    let (ha, hb) = (histogram(a), histogram(b));
    ha.iter().zip(&hb).map(|(x, y)| (x - y).abs()).sum::<f64>() / 2.0
}
