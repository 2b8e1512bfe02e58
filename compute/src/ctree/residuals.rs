//! Hierarchical prediction with closed-loop quantization: each level of the lattice is predicted
//! by the primal (multilinear) interpolation of the level above as the decoder reconstructs it,
//! and stores the residual quantized to a signed 7-bit code. The step of a level is the user's
//! step, raised where the level's residuals would not fit 7 bits, so no code is ever clamped and
//! every node reconstructs within half its level's step of the field (before pruning's exact
//! zeros, which change nothing). A node is pruned when it and its whole subtree code zero.
//! Of the nodes past the field's own samples (the lattice is 2^n + 1 a side), only the first
//! past each border at each level codes a residual (against the border's value, an anchor for
//! the cells that hold samples) with [`Border::Anchored`], none with [`Border::Free`]; the rest
//! code zero and prune.

use super::field::ScalarField;
use super::lattice::Lattice;
use super::tree::Border;

/// Largest magnitude of a code (the 7-bit range is −64..=63; ±63 keeps it symmetric).
pub const MAX_CODE: i32 = crate::shader_constants::CTREE_MAX_CODE as i32;

/// The quantized pyramid of a field: per level, the codes, the reconstructed values and which
/// nodes are internal (have a live child) or live (code ≠ 0 or internal).
#[derive(Clone, Debug)]
pub struct Residuals {
    /// The lattice.
    pub lattice: Lattice,
    /// The step of each level 0..=L, in fixed point.
    pub steps: Vec<i32>,
    /// Reconstructed values per level (level 0 holds the root only), dense lattice order.
    pub values: Vec<Vec<i32>>,
    /// Codes per level, dense lattice order.
    pub codes: Vec<Vec<i8>>,
    /// Whether a node has a live child, per level.
    pub internal: Vec<Vec<bool>>,
}

/// The primal prediction of the node at level-`l` coordinates `q` (`l` ≥ 2) from the values
/// of level `l` − 1: the mean of the 1, 2, 4 or 8 parent-level nodes around it, rounded down.
/// The decoder computes the same sum from the corners it holds.
pub fn predict(lat: &Lattice, l: u32, q: [u32; 3], above: &[i32]) -> i32 {
    let mut sum = 0i32;
    let mut odd = 0;
    let axes = lat.dims as usize;
    let mut lo = [0u32; 3];
    let mut hi = [0u32; 3];
    for k in 0..axes {
        lo[k] = q[k] / 2;
        hi[k] = q[k].div_ceil(2);
        if lo[k] != hi[k] {
            odd += 1;
        }
    }
    for c in 0..lat.brood() {
        let mut p = [0u32; 3];
        let mut skip = false;
        for k in 0..axes {
            let upper = (c >> k) & 1 == 1;
            if upper && lo[k] == hi[k] {
                skip = true;
            }
            p[k] = if upper { hi[k] } else { lo[k] };
        }
        if !skip {
            sum += above[lat.index(l - 1, p)];
        }
    }
    sum >> odd
}

/// The code of residual `t` at step `step`: rounded to nearest, halves away from zero.
pub fn quantize(t: i32, step: i32) -> i32 {
    if t >= 0 {
        (2 * t + step) / (2 * step)
    } else {
        -((-2 * t + step) / (2 * step))
    }
}

/// The level's step: the user's, or the smallest that fits the largest residual in ±63 codes.
pub fn level_step(user: i32, max_abs: i32) -> i32 {
    user.max((max_abs + MAX_CODE - 1) / MAX_CODE)
}

impl Residuals {
    /// Quantizes `field` with finest step `step` (fixed point, ≥ 1).
    pub fn build(field: &ScalarField, step: i32, border: Border) -> Residuals {
        let lat = field.lattice();
        let levels = lat.finest() as usize;
        let root_target = field.fixed_at([0; 3]);
        let root_step = level_step(step, root_target.abs());
        let root_code = quantize(root_target, root_step);
        let mut steps = vec![root_step];
        let mut values = vec![vec![root_code * root_step]];
        let mut codes = vec![vec![root_code as i8]];
        for l in 1..=levels as u32 {
            let count = lat.count(l);
            let spacing = lat.spacing(l);
            let mut residual = Vec::with_capacity(count);
            let mut prediction = Vec::with_capacity(count);
            for i in 0..count {
                let q = lat.coords(l, i);
                let p = if l == 1 {
                    values[0][0]
                } else {
                    predict(&lat, l, q, &values[l as usize - 1])
                };
                let at = q.map(|v| v * spacing);
                prediction.push(p);
                // Nodes past the field's samples are never read for themselves: see Border.
                residual.push(if field.codes(at, spacing, border) {
                    field.fixed_at(at) - p
                } else {
                    0
                });
            }
            let max_abs = residual.iter().map(|t| t.abs()).max().unwrap_or(0);
            let s = level_step(step, max_abs);
            let level_codes: Vec<i8> = residual.iter().map(|&t| quantize(t, s) as i8).collect();
            let level_values = prediction
                .iter()
                .zip(&level_codes)
                .map(|(&p, &c)| p + c as i32 * s)
                .collect();
            steps.push(s);
            codes.push(level_codes);
            values.push(level_values);
        }
        let mut internal: Vec<Vec<bool>> = vec![Vec::new(); levels + 1];
        internal[levels] = vec![false; lat.count(levels as u32)];
        for l in (0..levels as u32).rev() {
            let count = if l == 0 { 1 } else { lat.count(l) };
            let below = l as usize + 1;
            let flags = (0..count)
                .map(|i| {
                    let q = if l == 0 { [0; 3] } else { lat.coords(l, i) };
                    let open = lat.open_axes(l, q);
                    (0..lat.brood()).any(|c| {
                        if !child_exists(&lat, open, c) {
                            return false;
                        }
                        let j = lat.index(l + 1, lat.child(l, q, c));
                        codes[below][j] != 0 || internal[below][j]
                    })
                })
                .collect();
            internal[l as usize] = flags;
        }
        Residuals {
            lattice: lat,
            steps,
            values,
            codes,
            internal,
        }
    }

    /// Nodes kept at level `l`: every child of an internal node (the root at level 0).
    pub fn kept(&self, l: u32) -> usize {
        if l == 0 {
            return 1;
        }
        let lat = &self.lattice;
        let parents = if l == 1 { 1 } else { lat.count(l - 1) };
        (0..parents)
            .filter(|&i| self.internal[l as usize - 1][i])
            .map(|i| {
                let q = if l == 1 { [0; 3] } else { lat.coords(l - 1, i) };
                lat.child_count(lat.open_axes(l - 1, q)) as usize
            })
            .sum()
    }
}

/// Whether child `c` exists under a node with open axes `open`.
pub fn child_exists(lat: &Lattice, open: [bool; 3], c: u32) -> bool {
    (0..lat.dims).all(|k| (c >> k) & 1 == 0 || open[k as usize])
}
