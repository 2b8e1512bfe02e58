//! Multi-scale sliced Wasserstein distance between patch distributions (after Rabin et al.
//! 2011 and the SWD of Karras et al. 2018), calibrated on the exemplar itself.
//!
//! Per band of a Laplacian pyramid (the detail of each Gaussian octave that the next does not
//! hold, and the coarsest octave itself), `count` 7×7 RGB patches of each image (147 values)
//! are projected on the same random unit directions; per direction the sorted projections are
//! compared quantile by quantile, and the distance is the root of the mean squared difference
//! over directions and quantiles, in 8-bit levels. Bands rather than Gaussian octaves: a raw
//! patch's variance is mostly its mean colour, so random projections of Gaussian patches see
//! little more than a blurred histogram, and a blur or blocks hardly move them (measured on
//! the constructed cases of `tests/tests/quality.rs`: a blur of walnut scored 1.1× the
//! calibration unit with Gaussian octaves). Sets of equal size make
//! the comparison a plain sort; every comparison at an octave uses the same `count`, so the
//! finite-sample bias (two samples of one distribution are not at distance 0) is the same for
//! the calibration and the measurement, and their ratio is meaningful.
//!
//! The unit is the distance between the two disjoint halves of the exemplar (split across its
//! longer side): what two crops of one photograph of the material differ by, per band. The
//! ratio is the mean over the bands of each band's distance over its unit, so that every scale
//! counts alike: 1 means "as close to the exemplar as the exemplar is to itself"; a copy of
//! the exemplar is below 1, a blur, blocks or another material above.

use super::image::LinearImage;
use rand::seq::index::sample;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64Mcg;
use rayon::prelude::*;

/// Bands of the default pyramid: the finest detail, the next octave's, and the coarsest
/// octave itself.
pub const SWD_BANDS: usize = 3;

/// How patches are taken and compared.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct SwdParams {
    /// Side of a patch in pixels (odd).
    pub patch: usize,
    /// Octaves of the Gaussian pyramid, finest first.
    pub octaves: usize,
    /// Random directions per octave.
    pub directions: usize,
    /// Most patches compared per image and octave.
    pub max_patches: usize,
    /// An octave whose exemplar halves hold fewer patches than this is left out (its
    /// distance would be mostly sampling noise).
    pub min_patches: usize,
    /// Seed of the directions and of the patch samples.
    pub seed: u64,
}

impl Default for SwdParams {
    fn default() -> SwdParams {
        SwdParams {
            patch: 7,
            octaves: SWD_BANDS,
            directions: 128,
            max_patches: 4096,
            min_patches: 64,
            seed: 0x5744,
        }
    }
}

/// Patches of one image per octave, each `3 · patch²` values in row-major RGB order.
#[derive(Clone, Debug)]
pub struct PatchSets {
    octaves: Vec<LinearImage>,
    patch: usize,
}

impl PatchSets {
    /// The pyramid of `image` for `params.octaves` octaves.
    pub fn new(image: &LinearImage, params: &SwdParams) -> PatchSets {
        PatchSets {
            octaves: image.laplacian(params.octaves),
            patch: params.patch,
        }
    }

    /// Patches that fit entirely inside octave `o`.
    pub fn available(&self, o: usize) -> usize {
        let im = &self.octaves[o];
        let p = self.patch;
        if im.width < p || im.height < p {
            return 0;
        }
        (im.width - p + 1) * (im.height - p + 1)
    }

    /// `count` patches of octave `o`, sampled without repetition (all of them when `count`
    /// is what is available), deterministically from `seed`.
    fn sample(&self, o: usize, count: usize, seed: u64) -> Vec<f32> {
        let im = &self.octaves[o];
        let p = self.patch;
        let cols = im.width - p + 1;
        let available = self.available(o);
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let mut picks: Vec<usize> = sample(&mut rng, available, count.min(available)).into_vec();
        picks.sort_unstable();
        let mut out = Vec::with_capacity(picks.len() * 3 * p * p);
        for i in picks {
            let (x0, y0) = (i % cols, i / cols);
            for y in y0..y0 + p {
                for x in x0..x0 + p {
                    out.extend_from_slice(&im.at(x, y));
                }
            }
        }
        out
    }
}

/// The distance of one image to the exemplar, per octave and over all.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SwdReport {
    /// Distance per band used, finest first, in 8-bit levels.
    pub per_octave: Vec<f64>,
    /// Mean over the bands used.
    pub mean: f64,
    /// Mean over the bands of the band's distance over its calibration unit: 1 is the
    /// exemplar's own variability; NaN when the exemplar is too small for any band.
    pub ratio: f64,
    /// Each band's distance over its calibration unit, finest first: which scale an excess
    /// comes from (speckle in the finest band, layout in the coarsest).
    pub band_ratios: Vec<f64>,
}

impl SwdReport {
    /// [`SwdReport::band_ratios`] in the default pyramid's [`SWD_BANDS`] places, NaN for a
    /// band the calibration left out (too few patches in a small exemplar).
    pub fn bands(&self) -> [f64; SWD_BANDS] {
        std::array::from_fn(|b| self.band_ratios.get(b).copied().unwrap_or(f64::NAN))
    }
}

/// The exemplar's patch sets and its own variability, against which images are measured.
#[derive(Clone, Debug)]
pub struct SwdCalibration {
    params: SwdParams,
    exemplar: PatchSets,
    /// Patches compared per octave used (every comparison at an octave uses the same number).
    pub counts: Vec<usize>,
    /// The distance between the exemplar's two disjoint halves per octave used.
    pub unit: Vec<f64>,
    directions: Vec<Vec<f32>>,
}

impl SwdCalibration {
    /// Calibrates on `exemplar`: splits it into two disjoint halves across its longer side and
    /// measures their distance per octave.
    pub fn new(exemplar: &LinearImage, params: SwdParams) -> SwdCalibration {
        let (w, h) = (exemplar.width, exemplar.height);
        let (a, b) = if w >= h {
            (
                exemplar.crop(0, 0, w / 2, h),
                exemplar.crop(w / 2, 0, w - w / 2, h),
            )
        } else {
            (
                exemplar.crop(0, 0, w, h / 2),
                exemplar.crop(0, h / 2, w, h - h / 2),
            )
        };
        let (a, b) = (PatchSets::new(&a, &params), PatchSets::new(&b, &params));
        let whole = PatchSets::new(exemplar, &params);
        let counts: Vec<usize> = (0..params.octaves)
            .map(|o| a.available(o).min(b.available(o)).min(params.max_patches))
            .take_while(|&n| n >= params.min_patches)
            .collect();
        let dims = 3 * params.patch * params.patch;
        let directions = random_directions(params.directions * counts.len(), dims, params.seed);
        let mut calibration = SwdCalibration {
            params,
            exemplar: whole,
            counts,
            unit: Vec::new(),
            directions,
        };
        calibration.unit = (0..calibration.counts.len())
            .map(|o| calibration.octave_distance(o, &a, 1, &b, 2))
            .collect();
        calibration
    }

    /// Octaves the calibration uses (fewer than asked when the exemplar is small).
    pub fn octaves(&self) -> usize {
        self.counts.len()
    }

    /// The calibration unit: the mean of the per-octave distances between the halves.
    pub fn unit_mean(&self) -> f64 {
        mean(&self.unit)
    }

    /// The distance of `image` to the whole exemplar, at the calibration's patch counts.
    /// An image too small for an octave's count compares all the patches it has there
    /// against as many of the exemplar's.
    pub fn measure(&self, image: &LinearImage) -> SwdReport {
        let sets = PatchSets::new(image, &self.params);
        let per_octave: Vec<f64> = (0..self.counts.len())
            .map(|o| self.octave_distance(o, &sets, 3, &self.exemplar, 4))
            .collect();
        let ratios: Vec<f64> = per_octave
            .iter()
            .zip(&self.unit)
            .map(|(d, u)| d / u.max(f64::MIN_POSITIVE))
            .collect();
        SwdReport {
            // No band at all (an exemplar whose halves hold under `min_patches` patches even
            // at the finest band): no figure rather than a misleading 0.
            ratio: if ratios.is_empty() {
                f64::NAN
            } else {
                mean(&ratios)
            },
            mean: mean(&per_octave),
            per_octave,
            band_ratios: ratios,
        }
    }

    /// The distance at octave `o` between samples of two sets (tags seed their samples).
    fn octave_distance(
        &self,
        o: usize,
        a: &PatchSets,
        tag_a: u64,
        b: &PatchSets,
        tag_b: u64,
    ) -> f64 {
        let count = self.counts[o].min(a.available(o)).min(b.available(o));
        let seed = |tag: u64| self.params.seed ^ (tag << 32) ^ (o as u64) << 48;
        let pa = a.sample(o, count, seed(tag_a));
        let pb = b.sample(o, count, seed(tag_b));
        let d = self.params.directions;
        sliced_distance(&pa, &pb, &self.directions[o * d..(o + 1) * d]) * 255.0
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// `n` unit vectors of `dims` values, uniformly distributed on the sphere (normalized
/// Gaussians from Box–Muller).
fn random_directions(n: usize, dims: usize, seed: u64) -> Vec<Vec<f32>> {
    let mut rng = Pcg64Mcg::seed_from_u64(seed ^ 0xd1_2ec7_1015);
    (0..n)
        .map(|_| {
            let v: Vec<f64> = (0..dims)
                .map(|_| {
                    let u1: f64 = rng.random::<f64>().max(1e-300);
                    let u2: f64 = rng.random();
                    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
                })
                .collect();
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            v.iter().map(|x| (x / norm) as f32).collect()
        })
        .collect()
}

/// Root mean squared difference of the sorted projections of two equal-sized patch sets
/// (flattened, `dims` values each) over `directions`.
fn sliced_distance(a: &[f32], b: &[f32], directions: &[Vec<f32>]) -> f64 {
    let dims = directions[0].len();
    let n = a.len() / dims;
    debug_assert_eq!(a.len(), b.len());
    if n == 0 {
        return 0.0;
    }
    let project = |set: &[f32], d: &[f32]| -> Vec<f32> {
        let mut out: Vec<f32> = set
            .chunks_exact(dims)
            .map(|p| p.iter().zip(d).map(|(x, y)| x * y).sum())
            .collect();
        out.sort_unstable_by(f32::total_cmp);
        out
    };
    // Per-direction terms are computed in parallel but summed in direction order: a parallel
    // float sum's grouping follows the thread pool, so its last bits would vary by machine.
    let per_direction: Vec<f64> = directions
        .par_iter()
        .map(|d| {
            let (pa, pb) = (project(a, d), project(b, d));
            pa.iter()
                .zip(&pb)
                .map(|(x, y)| f64::from(x - y).powi(2))
                .sum::<f64>()
                / n as f64
        })
        .collect();
    let total: f64 = per_direction.iter().sum();
    (total / directions.len() as f64).sqrt()
}
