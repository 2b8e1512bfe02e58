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

/// A Gaussian pixel footprint on the target plane (texels): covariance σ_P² I + m mᵀ, isotropic
/// when the stretch m is zero, elongated along m otherwise (a grazing view's footprint, from
/// ray differentials).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Centre u_P.
    pub center: Vec2,
    /// Standard deviation σ_P (> 0) across the footprint.
    pub sigma: f32,
    /// The stretch m: the footprint's extra spread along its long axis (zero: isotropic).
    pub stretch: Vec2,
}

impl Footprint {
    /// An isotropic footprint.
    pub fn isotropic(center: Vec2, sigma: f32) -> Footprint {
        Footprint {
            center,
            sigma,
            stretch: Vec2::ZERO,
        }
    }

    /// The footprint whose covariance is `a aᵀ + b bᵀ` (two axes in texels), with σ_P at least
    /// `min_sigma` and its long axis's standard deviation at most `max_sigma`: σ_P² is the
    /// smaller eigenvalue, the stretch the larger one's excess along its eigenvector.
    pub fn from_axes(center: Vec2, a: Vec2, b: Vec2, min_sigma: f32, max_sigma: f32) -> Footprint {
        let (sxx, sxy, syy) = (
            a.x * a.x + b.x * b.x,
            a.x * a.y + b.x * b.y,
            a.y * a.y + b.y * b.y,
        );
        let half_trace = 0.5 * (sxx + syy);
        let root = (0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy).sqrt();
        let (large, small) = (half_trace + root, (half_trace - root).max(0.0));
        let sigma = small.sqrt().clamp(min_sigma, max_sigma);
        let long = large.sqrt().clamp(sigma, max_sigma);
        // The larger eigenvalue's eigenvector (either form, whichever is better conditioned).
        let dir = if sxx >= syy {
            Vec2::new(large - syy, sxy)
        } else {
            Vec2::new(sxy, large - sxx)
        };
        let dir = dir.try_normalize().unwrap_or(Vec2::X);
        Footprint {
            center,
            sigma,
            stretch: dir * (long * long - sigma * sigma).max(0.0).sqrt(),
        }
    }

    /// The texels the sum visits: the integer points of u_P ± [`FOOTPRINT_CUTOFF`] standard
    /// deviations along each axis (inclusive bounds).
    pub fn texel_box(&self) -> (IVec2, IVec2) {
        let r = if self.stretch == Vec2::ZERO {
            Vec2::splat(FOOTPRINT_CUTOFF * self.sigma)
        } else {
            let s2 = self.sigma * self.sigma;
            let m = self.stretch;
            Vec2::new((s2 + m.x * m.x).sqrt(), (s2 + m.y * m.y).sqrt()) * FOOTPRINT_CUTOFF
        };
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
    if fp.stretch != Vec2::ZERO {
        return element_stretched(u_i, n, j, fp, s, sigma_r);
    }
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

/// [`element`] for a stretched footprint: the footprint's precision matrix
/// P = (I − m mᵀ / (σ² + |m|²)) / σ² (Sherman–Morrison) where the isotropic form has I / σ², and
/// its normalization 1 / (2π σ √(σ² + |m|²)). Twin of `glint_element` with a stretch.
fn element_stretched(u_i: Vec2, n: Vec2, j: Mat2, fp: &Footprint, s: Vec2, sigma_r: f32) -> f32 {
    let (ih, ir) = (1.0 / (SIGMA_H * SIGMA_H), 1.0 / (sigma_r * sigma_r));
    let s2 = fp.sigma * fp.sigma;
    let m = fp.stretch;
    let long2 = s2 + m.length_squared();
    let (p00, p01, p11) = (
        (1.0 - m.x * m.x / long2) / s2,
        -(m.x * m.y / long2) / s2,
        (1.0 - m.y * m.y / long2) / s2,
    );
    let a = s - n;
    let e = fp.center - u_i;
    let jt = j.transpose();
    let mm = jt * j * ir;
    let (a00, a01, a11) = (
        mm.x_axis.x + ih + p00,
        mm.y_axis.x + p01,
        mm.y_axis.y + ih + p11,
    );
    let pe = Vec2::new(p00 * e.x + p01 * e.y, p01 * e.x + p11 * e.y);
    let b = jt * a * ir + pe;
    let c = a.length_squared() * ir + e.dot(pe);
    let det = a00 * a11 - a01 * a01;
    let quad = (a11 * b.x * b.x - 2.0 * a01 * b.x * b.y + a00 * b.y * b.y) / det;
    let ci = 1.0 / (2.0 * PI * SIGMA_H * SIGMA_H * 2.0 * PI * sigma_r * sigma_r);
    ci / (2.0 * PI * fp.sigma * long2.sqrt()) * (2.0 * PI / det.sqrt()) * (-0.5 * (c - quad)).exp()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ G_P(u) G_h(u − u_i) G_r(s − n − J(u − u_i)) du by the midpoint rule on a fine grid: the
    /// integral the element's closed form is.
    fn element_by_quadrature(
        u_i: Vec2,
        n: Vec2,
        j: Mat2,
        fp: &Footprint,
        s: Vec2,
        sigma_r: f32,
    ) -> f64 {
        let s2 = f64::from(fp.sigma * fp.sigma);
        let m = fp.stretch.as_dvec2();
        let cov =
            glam::DMat2::from_cols_array(&[s2 + m.x * m.x, m.x * m.y, m.x * m.y, s2 + m.y * m.y]);
        let inv = cov.inverse();
        let gauss2 = |d: glam::DVec2, inv: glam::DMat2, det: f64| {
            (-0.5 * d.dot(inv * d)).exp() / (2.0 * std::f64::consts::PI * det.sqrt())
        };
        let h2 = f64::from(SIGMA_H * SIGMA_H);
        let r2 = f64::from(sigma_r * sigma_r);
        let (step, half) = (0.01f64, 4.0f64);
        let mut sum = 0.0;
        let steps = (2.0 * half / step) as i32;
        for iy in 0..steps {
            for ix in 0..steps {
                let d = glam::DVec2::new(
                    -half + (f64::from(ix) + 0.5) * step,
                    -half + (f64::from(iy) + 0.5) * step,
                );
                let u = u_i.as_dvec2() + d;
                let gp = gauss2(u - fp.center.as_dvec2(), inv, cov.determinant());
                let gh = gauss2(d, glam::DMat2::IDENTITY / h2, h2 * h2);
                let a = (s - n).as_dvec2() - j.as_dmat2() * d;
                let gr = gauss2(a, glam::DMat2::IDENTITY / r2, r2 * r2);
                sum += gp * gh * gr * step * step;
            }
        }
        sum
    }

    #[test]
    fn a_stretched_footprint_integrates_like_the_quadrature_and_an_unstretched_one_is_unchanged() {
        let u_i = Vec2::new(3.0, -2.0);
        let n = Vec2::new(0.1, -0.05);
        let j = Mat2::from_cols(Vec2::new(0.02, 0.01), Vec2::new(-0.015, 0.03));
        let sigma_r = 0.05;
        for (center, sigma, stretch, s) in [
            (
                Vec2::new(3.4, -1.7),
                1.2,
                Vec2::new(2.0, 1.0),
                Vec2::new(0.12, -0.04),
            ),
            (
                Vec2::new(2.1, -2.5),
                0.8,
                Vec2::new(-0.5, 2.5),
                Vec2::new(0.08, -0.07),
            ),
        ] {
            let fp = Footprint {
                center,
                sigma,
                stretch,
            };
            let closed = f64::from(element(u_i, n, j, &fp, s, sigma_r));
            let numeric = element_by_quadrature(u_i, n, j, &fp, s, sigma_r);
            assert!(
                (closed - numeric).abs() <= 2e-3 * numeric.abs().max(1e-3),
                "{closed} vs {numeric}"
            );
        }
        let iso = Footprint::isotropic(Vec2::new(3.4, -1.7), 1.2);
        let closed = f64::from(element(u_i, n, j, &iso, Vec2::new(0.12, -0.04), sigma_r));
        let numeric = element_by_quadrature(u_i, n, j, &iso, Vec2::new(0.12, -0.04), sigma_r);
        assert!((closed - numeric).abs() <= 2e-3 * numeric.abs());
    }

    #[test]
    fn footprint_axes_become_width_and_stretch_with_the_same_covariance() {
        let (a, b) = (Vec2::new(6.0, 2.0), Vec2::new(-0.5, 1.5));
        let fp = Footprint::from_axes(Vec2::ZERO, a, b, 0.1, 100.0);
        let s2 = fp.sigma * fp.sigma;
        let m = fp.stretch;
        let cov = [s2 + m.x * m.x, m.x * m.y, s2 + m.y * m.y];
        let want = [
            a.x * a.x + b.x * b.x,
            a.x * a.y + b.x * b.y,
            a.y * a.y + b.y * b.y,
        ];
        for (c, w) in cov.iter().zip(want) {
            assert!(
                (c - w).abs() < 1e-3 * w.abs().max(1.0),
                "{cov:?} vs {want:?}"
            );
        }
        // A round footprint has no stretch; limits clamp both widths.
        let round = Footprint::from_axes(
            Vec2::ZERO,
            Vec2::new(2.0, 0.0),
            Vec2::new(0.0, 2.0),
            0.5,
            8.0,
        );
        assert!(round.stretch.length() < 1e-3 && (round.sigma - 2.0).abs() < 1e-5);
        let thin = Footprint::from_axes(
            Vec2::ZERO,
            Vec2::new(50.0, 0.0),
            Vec2::new(0.0, 0.1),
            0.5,
            8.0,
        );
        assert_eq!(thin.sigma, 0.5);
        assert!((thin.sigma.hypot(thin.stretch.length()) - 8.0).abs() < 1e-4);
    }
}
