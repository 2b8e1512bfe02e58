//! Random access to a compressed tree, in integers only, so the GLSL lookup
//! (`glsl/include/ctree/lookup.glsl`) returns the same value bit for bit. An evaluation holds the 2^d
//! corners of one cell per level (the thesis' "two active nodes" in 1D), starts at the forest's
//! level F from the dense pyramid and the indirection table, and descends: each corner of the
//! half-size cell is the primal prediction from the current corners plus its code times the
//! level's step, the code read from the record of the current corner that owns it. It stops
//! at the level asked for, or when no corner has a subtree (below, the field is the multilinear
//! interpolation of the corners), and interpolates the corners at the point.

use super::field::from_fixed;
use super::tree::{byte_code, CompressedTree, NO_SUBTREE};

pub use crate::shader_constants::{
    CTREE_LOD_FRAC_BITS as LOD_FRAC_BITS, CTREE_POS_FRAC_BITS as POS_FRAC_BITS,
    CTREE_WEIGHT_BITS as WEIGHT_BITS,
};

/// The corners of the current cell of an evaluation.
#[derive(Clone, Copy, Debug)]
struct Cell {
    level: u32,
    /// Lower corner, in level coordinates.
    base: [u32; 3],
    values: [i32; 8],
    records: [u32; 8],
}

impl CompressedTree {
    fn log2_spacing(&self, l: u32) -> u32 {
        self.lattice.n + 1 - l
    }

    /// The cell of level `l` (≤ F) holding `pos`, its corners read from the pyramid.
    fn forest_cell(&self, l: u32, pos: [u32; 3]) -> Cell {
        let lat = &self.lattice;
        let shift = self.log2_spacing(l) + POS_FRAC_BITS;
        let last_cell = lat.side(l) - 2;
        let mut base = [0u32; 3];
        for k in 0..lat.dims as usize {
            base[k] = (pos[k] >> shift).min(last_cell);
        }
        let mut cell = Cell {
            level: l,
            base,
            values: [0; 8],
            records: [NO_SUBTREE; 8],
        };
        let start = self.mip_starts[l as usize - 1] as usize;
        for e in 0..lat.brood() as usize {
            let q = corner(base, e);
            let i = lat.index(l, q);
            cell.values[e] = self.mipmap[start + i] as i32;
            if l == self.forest {
                cell.records[e] = self.indirection[i];
            }
        }
        cell
    }

    /// One level down: the half-size cell holding `pos`. `None` when no corner has a subtree.
    fn descend(&self, cell: &Cell, pos: [u32; 3]) -> Option<Cell> {
        let lat = &self.lattice;
        let d = lat.dims as usize;
        if cell.records[..lat.brood() as usize]
            .iter()
            .all(|&r| r == NO_SUBTREE)
        {
            return None;
        }
        let l = cell.level;
        let half = 1u32 << (self.log2_spacing(l) - 1 + POS_FRAC_BITS);
        let shift = self.log2_spacing(l) + POS_FRAC_BITS;
        let mut sub = [0u32; 3];
        for (k, s) in sub.iter_mut().enumerate().take(d) {
            *s = u32::from(pos[k] - (cell.base[k] << shift) >= half);
        }
        let step = self.steps[l as usize + 1];
        let scale = self.scales[l as usize];
        let mut next = Cell {
            level: l + 1,
            base: [0, 1, 2].map(|k| 2 * cell.base[k] + sub[k]),
            values: [0; 8],
            records: [NO_SUBTREE; 8],
        };
        for c in 0..lat.brood() as usize {
            let mut owner = 0usize;
            let mut child = 0u32;
            let mut odd = 0;
            let mut t = [0u32; 3];
            for k in 0..d {
                t[k] = sub[k] + ((c >> k) & 1) as u32;
                match t[k] {
                    2 => owner |= 1 << k,
                    1 => {
                        child |= 1 << k;
                        odd += 1;
                    }
                    _ => {}
                }
            }
            let mut sum = 0i32;
            for e in 0..lat.brood() as usize {
                let takes = (0..d).all(|k| {
                    let bit = (e >> k) & 1;
                    t[k] == 1 || (t[k] == 0 && bit == 0) || (t[k] == 2 && bit == 1)
                });
                if takes {
                    sum += cell.values[e];
                }
            }
            let prediction = sum >> odd;
            let record = cell.records[owner];
            let (code, sub_record) = if record == NO_SUBTREE {
                (0, NO_SUBTREE)
            } else {
                let q = corner(cell.base, owner);
                let open = lat.open_axes(l, q);
                let size = 1 + lat.child_count(open);
                let b = self.bytes[(record + 1 + lat.slot(open, child)) as usize];
                if b & 0x80 != 0 {
                    let address = record + size + (b & 0x7F) as u32 * scale;
                    (byte_code(self.bytes[address as usize]), address)
                } else {
                    (byte_code(b), NO_SUBTREE)
                }
            };
            next.values[c] = prediction + code * step;
            next.records[c] = sub_record;
        }
        Some(next)
    }

    /// The multilinear interpolation of a cell's corners at `pos`.
    fn interpolate(&self, cell: &Cell, pos: [u32; 3]) -> i32 {
        let d = self.lattice.dims as usize;
        let bits = self.log2_spacing(cell.level) + POS_FRAC_BITS;
        let mut v = cell.values;
        let mut count = 1usize << d;
        for (k, &p) in pos.iter().enumerate().take(d) {
            let rel = p - (cell.base[k] << bits);
            let w = if bits >= WEIGHT_BITS {
                rel >> (bits - WEIGHT_BITS)
            } else {
                rel << (WEIGHT_BITS - bits)
            } as i32;
            count /= 2;
            for e in 0..count {
                let (a, b) = (v[2 * e], v[2 * e + 1]);
                v[e] = a + (((b - a) * w) >> WEIGHT_BITS);
            }
        }
        v[0]
    }

    /// The value at level `l` (1 ..= L) at `pos` (finest spacings, [`POS_FRAC_BITS`] fraction,
    /// each within `0 ..= 2^n << POS_FRAC_BITS`), and the value one level finer when `finer`
    /// (equal to the first where the tree ends above `l`).
    fn evaluate(&self, l: u32, pos: [u32; 3], finer: bool) -> (i32, i32) {
        if l < self.forest {
            let at = self.interpolate(&self.forest_cell(l, pos), pos);
            let next = if finer {
                self.interpolate(&self.forest_cell(l + 1, pos), pos)
            } else {
                at
            };
            return (at, next);
        }
        let mut cell = self.forest_cell(self.forest, pos);
        while cell.level < l {
            match self.descend(&cell, pos) {
                Some(next) => cell = next,
                None => break,
            }
        }
        let at = self.interpolate(&cell, pos);
        if !finer || cell.level < l || l == self.lattice.finest() {
            return (at, at);
        }
        match self.descend(&cell, pos) {
            Some(next) => (at, self.interpolate(&next, pos)),
            None => (at, at),
        }
    }

    /// The value (fixed point) at `pos` (finest lattice spacings with [`POS_FRAC_BITS`]
    /// fractional bits, clamped to the field's samples) at level of detail `lod` (fixed point with
    /// [`LOD_FRAC_BITS`] fractional bits: 0 is the finest level, 1 the next coarser, fractions
    /// blend the two levels around).
    pub fn lookup_fixed(&self, pos: [u32; 3], lod: u32) -> i32 {
        let lat = &self.lattice;
        let mut clamped = [0u32; 3];
        for (k, c) in clamped.iter_mut().enumerate() {
            *c = pos[k].min((self.size[k] - 1) << POS_FRAC_BITS);
        }
        let pos = clamped;
        let finest = lat.finest() << LOD_FRAC_BITS;
        let target = finest.saturating_sub(lod).max(1 << LOD_FRAC_BITS);
        let level = target >> LOD_FRAC_BITS;
        let w = (target & ((1 << LOD_FRAC_BITS) - 1)) as i32;
        let (at, next) = self.evaluate(level, pos, w > 0);
        at + (((next - at) * w) >> LOD_FRAC_BITS)
    }

    /// The value at sample `p` of the field (finest level, no filtering), in fixed point.
    pub fn texel_fixed(&self, p: [u32; 3]) -> i32 {
        self.lookup_fixed(p.map(|v| v << POS_FRAC_BITS), 0)
    }

    /// Every sample of the field, decoded, in grey levels (x fastest).
    pub fn decode(&self) -> Vec<f32> {
        let [w, h, d] = self.size;
        let mut out = Vec::with_capacity((w * h * d) as usize);
        for z in 0..d {
            for y in 0..h {
                for x in 0..w {
                    out.push(from_fixed(self.texel_fixed([x, y, z])));
                }
            }
        }
        out
    }
}

/// Corner `e` (bit k = upper along axis k) of the cell with lower corner `base`.
fn corner(base: [u32; 3], e: usize) -> [u32; 3] {
    [
        base[0] + (e & 1) as u32,
        base[1] + ((e >> 1) & 1) as u32,
        base[2] + ((e >> 2) & 1) as u32,
    ]
}

impl CompressedTree {
    /// The fixed-point lattice position of `uv` ([0, 1]^d over the field, its samples at
    /// (i + 0.5) / size), clamped to the field's own samples; as `ctree_position` in GLSL.
    pub fn position(&self, uv: [f32; 3]) -> [u32; 3] {
        let mut pos = [0u32; 3];
        for (k, p) in pos.iter_mut().enumerate().take(self.lattice.dims as usize) {
            let x = uv[k] * (self.size[k] << POS_FRAC_BITS) as f32;
            let y = x - (1u32 << (POS_FRAC_BITS - 1)) as f32;
            let top = ((self.size[k] - 1) << POS_FRAC_BITS) as f32;
            *p = y.floor().clamp(0.0, top) as u32;
        }
        pos
    }

    /// The field at `uv` in grey levels, at level of detail `lod` (0 the finest; fractions
    /// blend two levels); as `ctree_sample` in GLSL.
    pub fn sample(&self, uv: [f32; 3], lod: f32) -> f32 {
        let l = (lod.clamp(0.0, 31.0) * (1u32 << LOD_FRAC_BITS) as f32) as u32;
        from_fixed(self.lookup_fixed(self.position(uv), l))
    }
}
