//! Range queries of the infinite map (Section 4.5 of the glint paper): the interval of the
//! blended normal over a power-of-two target square, from the four example intervals at the
//! square's position in its corners' patches, pushed through the same blend. Every step of the
//! blend is monotone (G and G⁻¹ are non-decreasing tables, the coefficients are non-negative and
//! the mean is a global constant), so blending the interval ends bounds every point of the
//! square, provided the coefficients are bounded over the square too: the bilinear weights
//! reach their extremes at the square's corners, and ‖w‖₂² = q(f_x) q(f_y) with
//! q(f) = (1 − f)² + f² convex, minimal at f = ½. The result is conservative, not tight.

use super::by_example::{BlendMode, ByExampleMap};
use super::error::GlintError;
use super::range_table::{NormalInterval, RangeTable};
use glam::{IVec2, Vec2};

/// Range of q(f) = (1 − f)² + f² over [a, b] ⊂ [0, 1].
fn q_range(a: f32, b: f32) -> (f32, f32) {
    let q = |f: f32| (1.0 - f) * (1.0 - f) + f * f;
    let lo = if a <= 0.5 && b >= 0.5 {
        0.5
    } else {
        q(a).min(q(b))
    };
    (lo, q(a).max(q(b)))
}

impl ByExampleMap {
    /// The interval of (n_x, n_y) over the target square [x, x + edge]² (texels), which must
    /// lie in one target patch; `edge` is a power of two up to the patch edge. One table lookup
    /// per corner patch.
    ///
    /// # Errors
    /// [`GlintError::Square`] when `edge` is not a power of two, the square crosses a patch
    /// border, or the table was built for another example or with fewer levels.
    pub fn range(
        &self,
        table: &RangeTable,
        x: i64,
        y: i64,
        edge: u32,
    ) -> Result<NormalInterval, GlintError> {
        let fail = |problem: String| GlintError::Square {
            x,
            y,
            edge,
            problem,
        };
        let l = self.patch() as i64;
        if !edge.is_power_of_two() || edge as i64 > l {
            return Err(fail(format!(
                "the edge must be a power of two up to the target patch edge {l}"
            )));
        }
        let level = edge.trailing_zeros() as usize;
        if table.size() != self.example().size() || level >= table.levels() {
            return Err(fail(format!(
                "the table covers a {}² example with {} levels; this map needs a {}² example and level {level}",
                table.size(),
                table.levels(),
                self.example().size()
            )));
        }
        let cell = IVec2::new(x.div_euclid(l) as i32, y.div_euclid(l) as i32);
        let local = (x.rem_euclid(l), y.rem_euclid(l));
        if local.0 + edge as i64 > l || local.1 + edge as i64 > l {
            return Err(fail(format!(
                "the square crosses a border of the {l}-texel target patches"
            )));
        }
        let lf = l as f32;
        let f0 = Vec2::new(local.0 as f32, local.1 as f32) / lf;
        let f1 = f0 + edge as f32 / lf;
        // Bounds of the bilinear weights per axis: index 0 is 1 − f, index 1 is f.
        let wx = [(1.0 - f1.x, 1.0 - f0.x), (f0.x, f1.x)];
        let wy = [(1.0 - f1.y, 1.0 - f0.y), (f0.y, f1.y)];
        let (qx, qy) = (q_range(f0.x, f1.x), q_range(f0.y, f1.y));
        let norm = if self.normalizes() {
            ((qx.0 * qy.0).sqrt(), (qx.1 * qy.1).sqrt())
        } else {
            (1.0, 1.0)
        };
        let mut lo = Vec2::ZERO;
        let mut hi = Vec2::ZERO;
        let mut none_lo = Vec2::splat(f32::INFINITY);
        let mut none_hi = Vec2::splat(f32::NEG_INFINITY);
        let mut hull_lo = Vec2::splat(f32::INFINITY);
        let mut hull_hi = Vec2::splat(f32::NEG_INFINITY);
        for (a, b) in [(0usize, 0usize), (1, 0), (0, 1), (1, 1)] {
            let o = self.vertex_origin(cell + IVec2::new(a as i32, b as i32));
            let px = o.x as i64 + local.0 + (1 - a as i64) * l;
            let py = o.y as i64 + local.1 + (1 - b as i64) * l;
            let input = table
                .query(level, px as usize, py as usize)
                .ok_or_else(|| fail(format!("example square at ({px}, {py}) leaves the table")))?;
            let w_lo = wx[a].0 * wy[b].0;
            let w_hi = wx[a].1 * wy[b].1;
            if w_hi > 0.0 {
                hull_lo = hull_lo.min(input.lo);
                hull_hi = hull_hi.max(input.hi);
            }
            if self.mode() == BlendMode::None {
                // The nearest vertex has the largest weight, at least ¼.
                if w_hi >= 0.25 {
                    none_lo = none_lo.min(input.lo);
                    none_hi = none_hi.max(input.hi);
                }
                continue;
            }
            // c_i = w_i / ‖w‖₂ never exceeds 1 (‖w‖₂ ≥ w_i).
            let (c_lo, c_hi) = (w_lo / norm.1, (w_hi / norm.0).min(1.0));
            for k in 0..2 {
                let y_lo = self.normal_to_blend(k, input.lo[k]).0;
                let y_hi = self.normal_to_blend(k, input.hi[k]).0;
                lo[k] += (c_lo * y_lo).min(c_hi * y_lo);
                hi[k] += (c_lo * y_hi).max(c_hi * y_hi);
            }
        }
        if self.mode() == BlendMode::None {
            return Ok(NormalInterval {
                lo: none_lo,
                hi: none_hi,
            });
        }
        if self.mode() == BlendMode::Linear {
            // Linear weights sum to 1: the blend is a convex combination of the inputs of the
            // corners that weigh anything over the square.
            lo = lo.max(hull_lo);
            hi = hi.min(hull_hi);
            return Ok(NormalInterval { lo, hi });
        }
        for k in 0..2 {
            lo[k] = self.blend_to_normal(k, lo[k]).0;
            hi[k] = self.blend_to_normal(k, hi[k]).0;
        }
        Ok(NormalInterval { lo, hi })
    }
}
