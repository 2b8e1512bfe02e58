//! Gaussianization tables of histogram-preserving blending (Heitz and Neyret 2018): per normal
//! component, G maps the example's distribution to the standard normal and G⁻¹ maps back. Both
//! are piecewise-linear tables of [`GLINT_TABLE_KNOTS`] knots; their derivatives (needed by the
//! chain rule, Eq. 12 of the glint paper) are the slopes of the segments, so they are the exact
//! derivatives of the interpolated functions and are read from the same knots. Both are
//! non-decreasing, which keeps the blend monotone for conservative range queries.

use super::example::NormalExample;
use crate::shader_constants::GLINT_TABLE_KNOTS;

/// Narrowest value domain of G: a constant component still gets a valid table.
const MIN_DOMAIN: f32 = 1e-6;

/// One piecewise-linear table over `[lo, hi]`, clamped outside (derivative 0 there).
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// Domain start.
    pub lo: f32,
    /// Domain end.
    pub hi: f32,
    /// Values at `lo + i (hi − lo) / (knots − 1)`.
    pub knots: Vec<f32>,
}

impl Table {
    /// Value and derivative at `x`. Twin of `glint_table` in `glint/by_example.glsl`.
    pub fn eval(&self, x: f32) -> (f32, f32) {
        let last = (self.knots.len() - 1) as f32;
        let step = (self.hi - self.lo) / last;
        let t = ((x - self.lo) / step).clamp(0.0, last);
        let j = t.floor().min(last - 1.0);
        let f = t - j;
        let (a, b) = (self.knots[j as usize], self.knots[j as usize + 1]);
        let slope = if x < self.lo || x > self.hi {
            0.0
        } else {
            (b - a) / step
        };
        (a + f * (b - a), slope)
    }
}

/// G and G⁻¹ for both normal components.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussianTables {
    /// G per component (x, y): example value → standard normal.
    pub forward: [Table; 2],
    /// G⁻¹ per component: standard normal → example value.
    pub inverse: [Table; 2],
}

impl GaussianTables {
    /// The tables of `example`'s two components, from its smoothed empirical distribution
    /// (rank + ½ over the texel count, linear between sorted values).
    pub fn new(example: &NormalExample) -> Self {
        let component = |k: usize| {
            let mut v: Vec<f32> = example.texels().iter().map(|n| n[k]).collect();
            v.sort_by(f32::total_cmp);
            v
        };
        let (sx, sy) = (component(0), component(1));
        GaussianTables {
            forward: [forward(&sx), forward(&sy)],
            inverse: [inverse(&sx), inverse(&sy)],
        }
    }

    /// The four tables' knots in the device layout: G_x, G_y, G⁻¹_x, G⁻¹_y.
    pub fn device_knots(&self) -> Vec<f32> {
        self.forward
            .iter()
            .chain(&self.inverse)
            .flat_map(|t| t.knots.iter().copied())
            .collect()
    }
}

/// Standard normal CDF.
fn phi(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// Inverse of [`phi`] by bisection (tables are small; exactness of the tail does not matter,
/// only monotonicity and determinism).
fn phi_inverse(p: f64) -> f64 {
    let (mut a, mut b) = (-10.0f64, 10.0f64);
    for _ in 0..80 {
        let m = 0.5 * (a + b);
        if phi(m) < p {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// The largest |G|: the standard-normal value of the top texel's rank.
fn gauss_max(count: usize) -> f64 {
    phi_inverse(1.0 - 0.5 / count as f64)
}

fn knots() -> usize {
    GLINT_TABLE_KNOTS as usize
}

fn forward(sorted: &[f32]) -> Table {
    let n = sorted.len();
    let lo = sorted[0];
    let hi = sorted[n - 1].max(lo + MIN_DOMAIN);
    let last = (knots() - 1) as f64;
    let knots = (0..knots())
        .map(|j| {
            let x = lo as f64 + (hi - lo) as f64 * j as f64 / last;
            // Smoothed CDF: rank m + ½ at sorted[m], linear up to the next distinct value.
            let m = sorted.partition_point(|&v| (v as f64) <= x).max(1) - 1;
            let rank = if m + 1 < n && sorted[m + 1] > sorted[m] {
                let (a, b) = (sorted[m] as f64, sorted[m + 1] as f64);
                m as f64 + ((x - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                m as f64
            };
            phi_inverse((rank + 0.5) / n as f64) as f32
        })
        .collect();
    Table { lo, hi, knots }
}

fn inverse(sorted: &[f32]) -> Table {
    let n = sorted.len();
    let g = gauss_max(n);
    let last = (knots() - 1) as f64;
    let knots = (0..knots())
        .map(|j| {
            let q =
                (phi(-g + 2.0 * g * j as f64 / last) * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
            let m = (q.floor() as usize).min(n.saturating_sub(2));
            let f = q - m as f64;
            let b = sorted[(m + 1).min(n - 1)] as f64;
            (sorted[m] as f64 + f * (b - sorted[m] as f64)) as f32
        })
        .collect();
    Table {
        lo: -g as f32,
        hi: g as f32,
        knots,
    }
}
