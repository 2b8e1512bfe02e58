//! Appearance vectors (Lefebvre & Hoppe 2006): each exemplar pixel of a stack level is
//! described by the Gaussian-weighted 5×5 neighbourhood around it (sampled at the level's
//! spacing), reduced by PCA to [`APPEARANCE_DIMS`] dimensions and quantized to integers.
//!
//! Quantization is what makes GPU and CPU agree exactly: every distance the synthesizer
//! computes is an integer sum of squared integer differences, which no driver can reorder or
//! fuse into a different result. The floats only live here, in a CPU preprocessing step whose
//! output is uploaded as integers.

use super::stack::border;
use nalgebra::{DMatrix, SymmetricEigen};

/// Dimensions of a reduced appearance vector.
pub const APPEARANCE_DIMS: usize = 8;

/// Largest magnitude of a quantized component: vectors are `i8`, so one vector is two 32-bit
/// words and a precomputed 4-diagonal neighbourhood is 32 bytes (see `neighbourhood.rs`).
/// The largest correction distance is 32 · (2 · 3 · 127)² ≈ 1.9·10⁷, far inside `u32`.
pub const APPEARANCE_QUANT_MAX: f64 = 127.0;

/// Radius of the analysed neighbourhood (5×5).
const RADIUS: i64 = 2;

/// Standard deviation, in neighbourhood samples, of the weighting that favours the centre.
const WEIGHT_SIGMA: f64 = 1.5;

/// The reduced appearance of one stack level.
#[derive(Clone, Debug)]
pub struct Appearance {
    /// One quantized vector per exemplar pixel, row-major.
    pub vectors: Vec<[i8; APPEARANCE_DIMS]>,
    /// Fraction of the neighbourhood variance the kept dimensions lose (0 = none).
    pub residual_variance: f64,
}

/// The appearance of several images of the same size in **one** PCA space: the basis and the
/// quantization scale come from the neighbourhoods of all images pooled, so a distance
/// between vectors of different images (or sums over several of them) compares like with
/// like. `features`, when given, holds one feature channel per image (`synth/feature.rs`),
/// appended to every sample before the analysis. Returns one vector list per image and the
/// residual variance of the pooled data.
pub(crate) fn shared_appearance(
    levels: &[&[[f32; 3]]],
    features: Option<&[&[f32]]>,
    w: u32,
    h: u32,
    spacing: u32,
    toroidal: bool,
) -> (Vec<Vec<[i8; APPEARANCE_DIMS]>>, f64) {
    let sized: Vec<SizedLevel> = levels
        .iter()
        .enumerate()
        .map(|(i, &pixels)| SizedLevel {
            pixels,
            feature: features.map(|f| f[i]),
            width: w,
            height: h,
            spacing,
        })
        .collect();
    let shared = sized_appearance(&sized, toroidal);
    (shared.vectors, shared.residual_variance)
}

/// One image of a pooled appearance space: its pixels, size and sampling spacing.
#[derive(Clone, Copy)]
pub(crate) struct SizedLevel<'a> {
    /// Row-major RGB in 0..=255.
    pub pixels: &'a [[f32; 3]],
    /// An optional fourth channel per pixel (the feature distance), same layout; either every
    /// image of a pooled space has one or none has.
    pub feature: Option<&'a [f32]>,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Neighbourhood sampling spacing.
    pub spacing: u32,
}

/// Fixed-point bits of [`SharedAppearance::offset_matrix`].
pub(crate) const OFFSET_MATRIX_BITS: u32 = 8;

/// Largest magnitude of an [`SharedAppearance::offset_matrix`] entry: one colour level then
/// moves a component by up to 2⁸ quantized units, past its whole ±127 range, so larger entries
/// would only saturate sooner; the bound keeps the multiscale offset move in 32-bit integers.
pub(crate) const OFFSET_MATRIX_MAX: i32 = 1 << 16;

/// A pooled appearance space over images of any sizes and spacings.
pub(crate) struct SharedAppearance {
    /// One vector list per image.
    pub vectors: Vec<Vec<[i8; APPEARANCE_DIMS]>>,
    /// Residual variance of the pooled data.
    pub residual_variance: f64,
    /// How a constant colour offset moves a quantized vector: component `d` moves by
    /// `Σ_c M[d][c] · b_c / 2^OFFSET_MATRIX_BITS` for an offset `b` in colour levels (the
    /// projection is linear, and a constant offset adds `w_δ · b` to every sample).
    pub offset_matrix: [[i32; 3]; APPEARANCE_DIMS],
}

/// [`shared_appearance`] over images of different sizes and spacings (the multiscale
/// synthesizer's per-depth space); for images of one size and spacing it computes exactly
/// what [`shared_appearance`] does.
pub(crate) fn sized_appearance(levels: &[SizedLevel], toroidal: bool) -> SharedAppearance {
    let side = (2 * RADIUS + 1) as usize;
    let with_feature = levels.first().is_some_and(|l| l.feature.is_some());
    assert!(
        levels.iter().all(|l| l.feature.is_some() == with_feature),
        "every image of a pooled appearance space has a feature channel or none has"
    );
    let channels = if with_feature { 4 } else { 3 };
    let dims = side * side * channels;
    let starts: Vec<usize> = levels
        .iter()
        .scan(0usize, |acc, l| {
            let start = *acc;
            *acc += l.width as usize * l.height as usize;
            Some(start)
        })
        .collect();
    let n: usize = levels
        .iter()
        .map(|l| l.width as usize * l.height as usize)
        .sum();
    let mut data = vec![0.0f64; n * dims];
    for (image, level) in levels.iter().enumerate() {
        let (w, h, spacing) = (level.width, level.height, level.spacing);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let pixel = starts[image] + (y * w as i64 + x) as usize;
                let row = &mut data[pixel * dims..][..dims];
                let mut j = 0;
                for dy in -RADIUS..=RADIUS {
                    for dx in -RADIUS..=RADIUS {
                        let weight = (-((dx * dx + dy * dy) as f64)
                            / (2.0 * WEIGHT_SIGMA * WEIGHT_SIGMA))
                            .exp();
                        let sx = border(x + dx * spacing as i64, w, toroidal);
                        let sy = border(y + dy * spacing as i64, h, toroidal);
                        let s = level.pixels[sy * w as usize + sx];
                        for c in s {
                            row[j] = weight * c as f64;
                            j += 1;
                        }
                        if let Some(feature) = level.feature {
                            row[j] = weight * f64::from(feature[sy * w as usize + sx]);
                            j += 1;
                        }
                    }
                }
            }
        }
    }
    let mut x = DMatrix::from_row_slice(n, dims, &data);
    for c in 0..dims {
        let mean = x.column(c).sum() / n as f64;
        x.column_mut(c).add_scalar_mut(-mean);
    }
    let covariance = x.transpose() * &x / n as f64;
    let eigen = SymmetricEigen::new(covariance);
    let mut order: Vec<usize> = (0..dims).collect();
    order.sort_by(|&a, &b| {
        eigen.eigenvalues[b]
            .total_cmp(&eigen.eigenvalues[a])
            .then(a.cmp(&b))
    });
    let total: f64 = eigen.eigenvalues.iter().map(|v| v.max(0.0)).sum();
    let kept: f64 = order[..APPEARANCE_DIMS]
        .iter()
        .map(|&i| eigen.eigenvalues[i].max(0.0))
        .sum();
    let residual_variance = if total > 0.0 { 1.0 - kept / total } else { 0.0 };
    // Basis vectors with a fixed sign (largest component positive), so the analysis does not
    // depend on the eigen solver's sign convention.
    let mut basis = DMatrix::<f64>::zeros(dims, APPEARANCE_DIMS);
    for (k, &i) in order[..APPEARANCE_DIMS].iter().enumerate() {
        let v = eigen.eigenvectors.column(i);
        let pivot = v
            .iter()
            .copied()
            .fold(0.0f64, |m, c| if c.abs() > m.abs() { c } else { m });
        let sign = if pivot < 0.0 { -1.0 } else { 1.0 };
        basis.set_column(k, &(v * sign));
    }
    let projected = x * &basis;
    let max_abs = projected.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = if max_abs > 1e-9 {
        APPEARANCE_QUANT_MAX / max_abs
    } else {
        1.0
    };
    let vectors = levels
        .iter()
        .enumerate()
        .map(|(image, l)| {
            (0..l.width as usize * l.height as usize)
                .map(|p| {
                    let row = starts[image] + p;
                    std::array::from_fn(|k| (projected[(row, k)] * scale).round() as i8)
                })
                .collect()
        })
        .collect();
    let offset_matrix = std::array::from_fn(|d| {
        std::array::from_fn(|c| {
            let mut m = 0.0f64;
            let mut j = 0;
            for dy in -RADIUS..=RADIUS {
                for dx in -RADIUS..=RADIUS {
                    let weight =
                        (-((dx * dx + dy * dy) as f64) / (2.0 * WEIGHT_SIGMA * WEIGHT_SIGMA)).exp();
                    m += weight * basis[(j * channels + c, d)];
                    j += 1;
                }
            }
            ((m * scale * (1u32 << OFFSET_MATRIX_BITS) as f64).round() as i64)
                .clamp(-OFFSET_MATRIX_MAX as i64, OFFSET_MATRIX_MAX as i64) as i32
        })
    });
    SharedAppearance {
        vectors,
        residual_variance,
        offset_matrix,
    }
}

/// Squared distance between two quantized vectors (exact).
pub fn appearance_distance(a: &[i8; APPEARANCE_DIMS], b: &[i8; APPEARANCE_DIMS]) -> u32 {
    a.iter()
        .zip(b)
        .map(|(&x, &y)| {
            let d = x as i32 - y as i32;
            (d * d) as u32
        })
        .sum()
}
