//! The infinite normal map by example (point queries, Sections 4.1–4.2 of "Example-Based
//! Microstructure Rendering with Constant Storage"): the target plane is a grid of target
//! patches of edge l; each grid vertex hashes to the origin of an example patch of edge 2l, and
//! every point blends the four patches of its cell's corners with bilinear weights. The seed is
//! per vertex, not per target patch: the four cells around a vertex read the same patch, so the
//! map is continuous across cell borders. Twin of `glsl/include/glint/by_example.glsl`.
//!
//! Per component, each mode maps an input value v to a blend space y (linear: v; variance
//! preserving: v − μ with μ the example mean; histogram preserving: G(v)), sums c_i y_i (c_i =
//! w_i, or w_i / ‖w‖₂ for the two preserving modes), and maps back (s, s + μ, G⁻¹(s)). The
//! Jacobian follows by the chain rule (Eqs. 7–12, with the derivative of G⁻¹ where the paper
//! prints G⁻¹). Like the paper, [`PointQuery::jacobian`] ignores how the weights vary with u;
//! [`PointQuery::jacobian_exact`] adds that term (O(|n_i − n_j| / l)) and is the exact
//! derivative of the map away from texel edges.

use super::error::GlintError;
use super::example::NormalExample;
use super::gaussianize::GaussianTables;
use crate::shader_constants::*;
use crate::shading::reference::rng_hash;
use glam::{IVec2, Mat2, UVec2, Vec2};

/// How the four example patches of a point are combined.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BlendMode {
    /// The patch of the nearest vertex (largest weight) alone: seams, but none visible for
    /// flakes (constant normals, zero Jacobian), which blending would over-smooth.
    None,
    /// Σ w_i n_i (Eq. 4): loses contrast between patch centres.
    Linear,
    /// (Σ w_i n_i − μ) / ‖w‖₂ + μ (Eq. 5), μ the example's global mean.
    Variance,
    /// G⁻¹ of the variance-preserving blend of G(n_i) (Eq. 6).
    Histogram,
}

impl BlendMode {
    /// The mode's `GLINT_BLEND_*` constant.
    pub fn code(self) -> u32 {
        match self {
            BlendMode::None => GLINT_BLEND_NONE,
            BlendMode::Linear => GLINT_BLEND_LINEAR,
            BlendMode::Variance => GLINT_BLEND_VARIANCE,
            BlendMode::Histogram => GLINT_BLEND_HISTOGRAM,
        }
    }

    /// All modes, for tests and tables.
    pub const ALL: [BlendMode; 4] = [
        BlendMode::None,
        BlendMode::Linear,
        BlendMode::Variance,
        BlendMode::Histogram,
    ];
}

/// A normal and its Jacobians at one point of the target.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointQuery {
    /// (n_x, n_y) of the blended normal.
    pub normal: Vec2,
    /// ∂n/∂u by Eqs. 10–12 (the paper's: the weights' own variation is ignored).
    pub jacobian: Mat2,
    /// ∂n/∂u with the weights' variation: the exact derivative away from texel edges.
    pub jacobian_exact: Mat2,
}

/// The four corner inputs of a point: example position, bilinear weight and its gradient.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Corner {
    pub p: Vec2,
    pub w: f32,
    pub dw: Vec2,
}

/// An infinite, non-repeating normal map from an example (constant storage).
#[derive(Clone, Debug)]
pub struct ByExampleMap {
    example: NormalExample,
    tables: GaussianTables,
    mean: Vec2,
    patch: u32,
    seed: u32,
    mode: BlendMode,
}

impl ByExampleMap {
    /// The map of `example` with target patches of edge `patch` texels (the paper uses a
    /// quarter of the example edge; example patches are twice as large), vertex origins hashed
    /// from `seed`.
    ///
    /// # Errors
    /// [`GlintError::Patch`] when `patch` is not a power of two from 2 to a quarter of the
    /// example edge.
    pub fn new(
        example: NormalExample,
        patch: u32,
        seed: u32,
        mode: BlendMode,
    ) -> Result<Self, GlintError> {
        let size = example.size() as u32;
        if !patch.is_power_of_two() || patch < 2 || patch > size / 4 {
            return Err(GlintError::Patch {
                patch,
                size,
                max: size / 4,
            });
        }
        let tables = GaussianTables::new(&example);
        let mean = example.mean();
        Ok(ByExampleMap {
            example,
            tables,
            mean,
            patch,
            seed,
            mode,
        })
    }

    /// The example.
    pub fn example(&self) -> &NormalExample {
        &self.example
    }

    /// The Gaussianization tables.
    pub fn tables(&self) -> &GaussianTables {
        &self.tables
    }

    /// Target patch edge in texels.
    pub fn patch(&self) -> u32 {
        self.patch
    }

    /// The hash seed of the vertex origins.
    pub fn seed(&self) -> u32 {
        self.seed
    }

    /// The blending mode.
    pub fn mode(&self) -> BlendMode {
        self.mode
    }

    /// The example mean μ of variance-preserving blending.
    pub fn mean(&self) -> Vec2 {
        self.mean
    }

    /// Origin (lower corner) in the example of grid vertex `v`'s patch of edge 2l: uniform in
    /// [0, n − 2l) per axis, so that the patch and its bilinear neighbours stay inside.
    pub fn vertex_origin(&self, v: IVec2) -> UVec2 {
        let range = self.example.size() as u32 - 2 * self.patch;
        let h = rng_hash(v.x as u32 ^ rng_hash(v.y as u32 ^ rng_hash(self.seed)));
        UVec2::new(h % range, rng_hash(h) % range)
    }

    /// The cell of target point `u` (in texels) and its four corners (order (0,0), (1,0),
    /// (0,1), (1,1)).
    pub(crate) fn corners(&self, u: Vec2) -> (IVec2, [Corner; 4]) {
        let l = self.patch as f32;
        let cell_f = (u / l).floor();
        let f = u / l - cell_f;
        let cell = cell_f.as_ivec2();
        let local = u - cell_f * l;
        let wx = [1.0 - f.x, f.x];
        let wy = [1.0 - f.y, f.y];
        let dw = [-1.0 / l, 1.0 / l];
        let corners = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(a, b)| {
            let o = self.vertex_origin(cell + IVec2::new(a, b)).as_vec2();
            let shift = Vec2::new((1 - a) as f32 * l, (1 - b) as f32 * l);
            Corner {
                p: o + local + shift,
                w: wx[a as usize] * wy[b as usize],
                dw: Vec2::new(
                    dw[a as usize] * wy[b as usize],
                    wx[a as usize] * dw[b as usize],
                ),
            }
        });
        (cell, corners)
    }

    /// Input value v of component k → blend space (value, derivative).
    pub(crate) fn normal_to_blend(&self, k: usize, v: f32) -> (f32, f32) {
        match self.mode {
            BlendMode::None | BlendMode::Linear => (v, 1.0),
            BlendMode::Variance => (v - self.mean[k], 1.0),
            BlendMode::Histogram => self.tables.forward[k].eval(v),
        }
    }

    /// Blend space → output value of component k (value, derivative).
    pub(crate) fn blend_to_normal(&self, k: usize, s: f32) -> (f32, f32) {
        match self.mode {
            BlendMode::None | BlendMode::Linear => (s, 1.0),
            BlendMode::Variance => (s + self.mean[k], 1.0),
            BlendMode::Histogram => self.tables.inverse[k].eval(s),
        }
    }

    /// Whether the mode divides the weights by ‖w‖₂.
    pub(crate) fn normalizes(&self) -> bool {
        matches!(self.mode, BlendMode::Variance | BlendMode::Histogram)
    }

    /// The normal and Jacobians at target point `u` (texels; any finite point of the plane
    /// where u / l fits an `i32`).
    pub fn point(&self, u: Vec2) -> PointQuery {
        let (_, corners) = self.corners(u);
        let samples = corners.map(|c| self.example.sample(c.p));
        if self.mode == BlendMode::None {
            let mut best = 0;
            for i in 1..4 {
                if corners[i].w > corners[best].w {
                    best = i;
                }
            }
            let (normal, j) = samples[best];
            return PointQuery {
                normal,
                jacobian: j,
                jacobian_exact: j,
            };
        }
        // Coefficients c_i and their gradients.
        let (mut c, mut dc) = ([0.0f32; 4], [Vec2::ZERO; 4]);
        if self.normalizes() {
            let mut w2 = 0.0;
            let mut dw2 = Vec2::ZERO;
            for k in &corners {
                w2 += k.w * k.w;
                dw2 += k.w * k.dw;
            }
            let norm = w2.sqrt();
            let d_norm = dw2 / norm;
            for i in 0..4 {
                c[i] = corners[i].w / norm;
                dc[i] = corners[i].dw / norm - corners[i].w * d_norm / (norm * norm);
            }
        } else {
            for i in 0..4 {
                c[i] = corners[i].w;
                dc[i] = corners[i].dw;
            }
        }
        let mut normal = Vec2::ZERO;
        let mut rows = [[Vec2::ZERO; 2]; 2]; // [component][paper, exact]
        for k in 0..2 {
            let (mut s, mut grad, mut grad_w) = (0.0f32, Vec2::ZERO, Vec2::ZERO);
            for i in 0..4 {
                let (v, jac) = samples[i];
                let (y, dy) = self.normal_to_blend(k, v[k]);
                s += c[i] * y;
                grad += c[i] * dy * jac.row(k);
                grad_w += y * dc[i];
            }
            let (n, dn) = self.blend_to_normal(k, s);
            normal[k] = n;
            rows[k] = [dn * grad, dn * (grad + grad_w)];
        }
        let mat = |m: usize| {
            Mat2::from_cols_array(&[rows[0][m].x, rows[1][m].x, rows[0][m].y, rows[1][m].y])
        };
        PointQuery {
            normal,
            jacobian: mat(0),
            jacobian_exact: mat(1),
        }
    }
}
