//! The P-NDF of a pixel footprint over the infinite map (Eqs. 1–3 of the glint paper, with
//! the closed form of Yan et al. 2016) and its importance sampling (Section 5.4). Twin of
//! `glsl/include/glint/pndf.glsl`.
//!
//! Every texel i of the target plane (the integer point u_i) is one Gaussian element in
//! position × normal: its normal n_i and Jacobian J_i come from the point query at u_i, its
//! positional width is σ_h = 1 / √(8 ln 2) texels (a full width at half maximum of one texel)
//! and its normal width the intrinsic roughness σ_r. For a footprint G_P (isotropic, centre
//! u_P, width σ_P, in texels) and a half vector s = (h_x, h_y):
//!
//! ```text
//! D_P(s) = Σ_i c_i / (2π σ_P²) · 2π / √det A · exp(−½ (c − bᵀ A⁻¹ b))
//! A = I/σ_h² + J_iᵀ J_i / σ_r² + I/σ_P²,  b = J_iᵀ a / σ_r² + e / σ_P²,  c = |a|²/σ_r² + |e|²/σ_P²
//! a = s − n_i,  e = u_P − u_i,  c_i = 1 / (2π σ_h² · 2π σ_r²)
//! ```
//!
//! so that D_P integrates to 1 over s (it is a density of s, which is already the projected
//! area measure of the half vector). The sum runs over the texels of the footprint's box
//! u_P ± [`FOOTPRINT_CUTOFF`] σ_P.
//!
//! - [`ByExampleMap::pndf`]: the pruned sum. The box is covered by aligned power-of-two
//!   squares (inside one target patch each); a square is subdivided (explicit stack) only when
//!   s lies in its blended normal interval widened by [`pruning_margin`]; single texels are
//!   evaluated.
//! - [`MaterializedMap`]: the explicit method. The infinite map is written out texel by texel
//!   over a rectangle (what an explicit normal map of that area would store) and the sum runs
//!   over every texel of the box without pruning: the oracle of the pruned sum.
//! - [`SampleTexels`]: importance sampling from the 4 texels around the shading point: a texel
//!   by its bilinear weight, then s from its element's normal marginal
//!   N(n_i, σ_r² I + σ_h² J_i J_iᵀ). [`SampleTexels::pdf`] is the density of exactly that
//!   procedure (a 4-component Gaussian mixture), which is what MIS weights need: it is not
//!   D_P.

use super::by_example::ByExampleMap;
use super::range_table::{NormalInterval, RangeTable};
use glam::{IVec2, Mat2, Vec2};
use std::f32::consts::PI;

/// Positional width of a texel's element: σ_h = 1 / √(8 ln 2) (FWHM one texel).
pub const SIGMA_H: f32 = 0.424_660_9;
/// The footprint box is u_P ± this many σ_P.
pub const FOOTPRINT_CUTOFF: f32 = 3.0;
/// The normal interval of a square is widened by this many σ_r …
pub const ROUGHNESS_CUTOFF: f32 = 4.0;
/// … and by the spread J·Δu of an element over this many σ_h, with |J| bounded by the
/// interval's own width (see [`pruning_margin`]).
pub const JACOBIAN_CUTOFF: f32 = 3.0;
/// Deepest stack of the traversal: 3 pending siblings per level for up to 16 levels.
pub const STACK_DEPTH: usize = 48;

/// An isotropic Gaussian pixel footprint on the target plane (texels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Centre u_P.
    pub center: Vec2,
    /// Standard deviation σ_P (> 0).
    pub sigma: f32,
}

impl Footprint {
    /// The texels the sum visits: the integer points of u_P ± [`FOOTPRINT_CUTOFF`] σ_P
    /// (inclusive bounds).
    pub fn texel_box(&self) -> (IVec2, IVec2) {
        let r = FOOTPRINT_CUTOFF * self.sigma;
        (
            (self.center - r).ceil().as_ivec2(),
            (self.center + r).floor().as_ivec2(),
        )
    }
}

/// Work done by one pruned evaluation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PndfStats {
    /// Squares whose range was queried.
    pub squares: u32,
    /// Texels whose element was evaluated.
    pub texels: u32,
}

/// Per-component widening of a square's interval before testing s: ROUGHNESS_CUTOFF σ_r plus
/// JACOBIAN_CUTOFF σ_h (|J_x| + |J_y|) with each Jacobian entry bounded by the interval width
/// (a bilinear cell's derivative is a difference of two of its texels, which the interval
/// contains). Twin of `glint_pruning_margin`.
pub fn pruning_margin(iv: &NormalInterval, sigma_r: f32) -> Vec2 {
    ROUGHNESS_CUTOFF * sigma_r + JACOBIAN_CUTOFF * SIGMA_H * 2.0 * (iv.hi - iv.lo)
}

/// One element's contribution ∫ G_P G_i du for the texel at `u_i` with normal `n`, Jacobian
/// `j`. Twin of `glint_element`.
pub fn element(u_i: Vec2, n: Vec2, j: Mat2, fp: &Footprint, s: Vec2, sigma_r: f32) -> f32 {
    let (ih, ir, ip) = (
        1.0 / (SIGMA_H * SIGMA_H),
        1.0 / (sigma_r * sigma_r),
        1.0 / (fp.sigma * fp.sigma),
    );
    let a = s - n;
    let e = fp.center - u_i;
    let jt = j.transpose();
    let m = jt * j * ir;
    let (a00, a01, a11) = (m.x_axis.x + ih + ip, m.y_axis.x, m.y_axis.y + ih + ip);
    let b = jt * a * ir + e * ip;
    let c = a.length_squared() * ir + e.length_squared() * ip;
    let det = a00 * a11 - a01 * a01;
    // bᵀ A⁻¹ b with A⁻¹ = [a11, −a01; −a01, a00] / det.
    let quad = (a11 * b.x * b.x - 2.0 * a01 * b.x * b.y + a00 * b.y * b.y) / det;
    let ci = 1.0 / (2.0 * PI * SIGMA_H * SIGMA_H * 2.0 * PI * sigma_r * sigma_r);
    ci / (2.0 * PI * fp.sigma * fp.sigma) * (2.0 * PI / det.sqrt()) * (-0.5 * (c - quad)).exp()
}

/// The aligned edge of the start squares of a box of extent `extent` texels: the power of two
/// at or above it, at most the patch edge.
pub(crate) fn start_edge(extent: i32, patch: u32) -> i32 {
    (extent.max(1) as u32).next_power_of_two().min(patch) as i32
}

impl ByExampleMap {
    /// D_P(s) by the pruned traversal (see the module), with its work.
    ///
    /// # Panics
    /// If `table` is not this map's (wrong example edge or too few levels).
    pub fn pndf(
        &self,
        table: &RangeTable,
        fp: &Footprint,
        s: Vec2,
        sigma_r: f32,
    ) -> (f32, PndfStats) {
        let (lo, hi) = fp.texel_box();
        let mut stats = PndfStats::default();
        if lo.x > hi.x || lo.y > hi.y {
            return (0.0, stats);
        }
        let edge0 = start_edge((hi - lo + 1).max_element(), self.patch());
        let (s0, s1) = (
            IVec2::new(lo.x.div_euclid(edge0), lo.y.div_euclid(edge0)),
            IVec2::new(hi.x.div_euclid(edge0), hi.y.div_euclid(edge0)),
        );
        let mut sum = 0.0f32;
        let mut stack: Vec<(IVec2, i32)> = Vec::with_capacity(STACK_DEPTH);
        for sy in s0.y..=s1.y {
            for sx in s0.x..=s1.x {
                stack.push((IVec2::new(sx, sy) * edge0, edge0));
                while let Some((p, edge)) = stack.pop() {
                    // Clip to the box.
                    if p.x > hi.x || p.y > hi.y || p.x + edge <= lo.x || p.y + edge <= lo.y {
                        continue;
                    }
                    if edge == 1 {
                        stats.texels += 1;
                        let u = p.as_vec2();
                        let q = self.point(u);
                        sum += element(u, q.normal, q.jacobian_exact, fp, s, sigma_r);
                        continue;
                    }
                    stats.squares += 1;
                    let iv = self
                        .range(table, p.x as i64, p.y as i64, edge as u32)
                        .expect("aligned squares lie in one target patch of a matching table");
                    if !iv.contains(s, 0.0) {
                        let m = pruning_margin(&iv, sigma_r);
                        if !(s.cmpge(iv.lo - m).all() && s.cmple(iv.hi + m).all()) {
                            continue;
                        }
                    }
                    let h = edge / 2;
                    for (dx, dy) in [(1, 1), (0, 1), (1, 0), (0, 0)] {
                        stack.push((p + IVec2::new(dx * h, dy * h), h));
                    }
                }
            }
        }
        (sum, stats)
    }
}

/// The explicit method: the infinite map written out texel by texel over a rectangle (normal
/// and Jacobian per texel, what a materialized normal map of that area stores), evaluated
/// without pruning.
#[derive(Clone, Debug)]
pub struct MaterializedMap {
    origin: IVec2,
    width: usize,
    height: usize,
    normals: Vec<Vec2>,
    jacobians: Vec<Mat2>,
}

impl MaterializedMap {
    /// The texels [origin, origin + (width, height)) of `map`.
    pub fn new(map: &ByExampleMap, origin: IVec2, width: usize, height: usize) -> Self {
        let mut normals = Vec::with_capacity(width * height);
        let mut jacobians = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let q = map.point((origin + IVec2::new(x as i32, y as i32)).as_vec2());
                normals.push(q.normal);
                jacobians.push(q.jacobian_exact);
            }
        }
        MaterializedMap {
            origin,
            width,
            height,
            normals,
            jacobians,
        }
    }

    /// The materialized texels of footprint `fp`'s box (with the same texel margin).
    pub fn covering(map: &ByExampleMap, fp: &Footprint) -> Self {
        let (lo, hi) = fp.texel_box();
        let size = (hi - lo + 1).max(IVec2::ZERO);
        Self::new(map, lo, size.x as usize, size.y as usize)
    }

    /// Bytes of the stored texels (2 + 4 floats each).
    pub fn bytes(&self) -> u64 {
        (self.normals.len() * 24) as u64
    }

    /// The stored normal and Jacobian of texel `u` (inside the rectangle).
    pub fn texel(&self, u: IVec2) -> (Vec2, Mat2) {
        let d = u - self.origin;
        let i = d.y as usize * self.width + d.x as usize;
        (self.normals[i], self.jacobians[i])
    }

    /// D_P(s) summed over every stored texel of the footprint's box, no pruning.
    ///
    /// # Panics
    /// If the box leaves the rectangle.
    pub fn pndf(&self, fp: &Footprint, s: Vec2, sigma_r: f32) -> f32 {
        let (lo, hi) = fp.texel_box();
        let end = self.origin + IVec2::new(self.width as i32, self.height as i32);
        assert!(
            lo.x > hi.x || (lo.cmpge(self.origin).all() && hi.cmplt(end).all()),
            "footprint box {lo}..={hi} leaves the materialized map {}..{end}",
            self.origin
        );
        let mut sum = 0.0;
        for y in lo.y..=hi.y {
            for x in lo.x..=hi.x {
                let u = IVec2::new(x, y);
                let (n, j) = self.texel(u);
                sum += element(u.as_vec2(), n, j, fp, s, sigma_r);
            }
        }
        sum
    }
}

/// The 4 texels around a shading point, with their bilinear weights: the mixture that
/// importance sampling draws s from.
#[derive(Clone, Copy, Debug)]
pub struct SampleTexels {
    /// Bilinear weights (sum 1), order (0,0), (1,0), (0,1), (1,1) from floor(u).
    pub weights: [f32; 4],
    /// The texels' normals.
    pub normals: [Vec2; 4],
    /// Covariance σ_r² I + σ_h² J Jᵀ of each texel's normal marginal.
    pub covariances: [Mat2; 4],
}

impl SampleTexels {
    /// The texels around `u` (texels) of `map` for intrinsic roughness `sigma_r`.
    pub fn new(map: &ByExampleMap, u: Vec2, sigma_r: f32) -> Self {
        let base = u.floor();
        let f = u - base;
        let wx = [1.0 - f.x, f.x];
        let wy = [1.0 - f.y, f.y];
        let mut t = SampleTexels {
            weights: [0.0; 4],
            normals: [Vec2::ZERO; 4],
            covariances: [Mat2::ZERO; 4],
        };
        for i in 0..4 {
            let (a, b) = (i & 1, i >> 1);
            let q = map.point(base + Vec2::new(a as f32, b as f32));
            t.weights[i] = wx[a] * wy[b];
            t.normals[i] = q.normal;
            t.covariances[i] = covariance(q.jacobian_exact, sigma_r);
        }
        t
    }

    /// Draws s with `u` in [0, 1)³ (u.z picks the texel). Twin of `glint_sample_s`.
    pub fn sample(&self, u: glam::Vec3) -> Vec2 {
        let mut pick = 3;
        let mut acc = 0.0;
        for i in 0..4 {
            acc += self.weights[i];
            if u.z < acc {
                pick = i;
                break;
            }
        }
        // Box–Muller, then the Cholesky factor of the covariance.
        let r = (-2.0 * (1.0 - u.x).ln()).sqrt();
        let phi = 2.0 * PI * u.y;
        let z = Vec2::new(r * phi.cos(), r * phi.sin());
        let c = self.covariances[pick];
        let l00 = c.x_axis.x.sqrt();
        let l10 = c.x_axis.y / l00;
        let l11 = (c.y_axis.y - l10 * l10).max(0.0).sqrt();
        self.normals[pick] + Vec2::new(l00 * z.x, l10 * z.x + l11 * z.y)
    }

    /// Density of s under [`SampleTexels::sample`]. Twin of `glint_sample_pdf`.
    pub fn pdf(&self, s: Vec2) -> f32 {
        let mut p = 0.0;
        for i in 0..4 {
            if self.weights[i] > 0.0 {
                p += self.weights[i] * gaussian2(s - self.normals[i], self.covariances[i]);
            }
        }
        p
    }
}

/// σ_r² I + σ_h² J Jᵀ.
pub(crate) fn covariance(j: Mat2, sigma_r: f32) -> Mat2 {
    let r2 = sigma_r * sigma_r;
    j * j.transpose() * (SIGMA_H * SIGMA_H) + Mat2::from_diagonal(Vec2::splat(r2))
}

/// The density of N(0, c) at d.
pub(crate) fn gaussian2(d: Vec2, c: Mat2) -> f32 {
    let det = c.determinant();
    let inv = c.inverse();
    (-0.5 * d.dot(inv * d)).exp() / (2.0 * PI * det.sqrt())
}
