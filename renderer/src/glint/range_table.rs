//! Range min/max queries in O(1) over the example (Section 4.3–4.4 of the glint paper): a
//! square-only 2D sparse table. Level k holds, for every start (x, y), the minimum and maximum
//! of n_x and n_y over the example square [x, x + 2^k]² of the bilinearly interpolated map,
//! i.e. over its (2^k + 1)² texels, so one lookup bounds a power-of-two square of any start.
//! (The paper stores levels from 2 texels and reads single texels directly; with bilinear
//! interpolation level 0 is the 2×2 texels of one cell.) Levels go up to the target patch edge.
//!
//! Each entry packs four 16-bit values: [min n_x | min n_y << 16, max n_x | max n_y << 16],
//! n in [−1, 1] mapped to [0, 65535], minima rounded down and maxima up, so dequantized
//! intervals always contain the true ones. Starts whose square leaves the example hold
//! [`EMPTY`]. The device builds the table bottom-up, one dispatch per level
//! (`glsl/render/glint_range_level.comp`); [`RangeTable::build`] is its exact CPU twin.

use super::example::NormalExample;
use glam::Vec2;

/// A packed entry that contains nothing (a start whose square leaves the example).
pub const EMPTY: [u32; 2] = [0xFFFF_FFFF, 0];

/// Largest quantized value.
const Q_MAX: f64 = 65535.0;

/// A closed interval of (n_x, n_y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalInterval {
    /// Minimum per component.
    pub lo: Vec2,
    /// Maximum per component.
    pub hi: Vec2,
}

impl NormalInterval {
    /// Whether `n` lies inside, widened by `slack` per component.
    pub fn contains(&self, n: Vec2, slack: f32) -> bool {
        n.cmpge(self.lo - slack).all() && n.cmple(self.hi + slack).all()
    }
}

fn quantize(v: f32, up: bool) -> u32 {
    let q = (v as f64 + 1.0) * 0.5 * Q_MAX;
    let q = if up { q.ceil() } else { q.floor() };
    q.clamp(0.0, Q_MAX) as u32
}

fn dequantize(q: u32) -> f32 {
    (q as f64 / Q_MAX * 2.0 - 1.0) as f32
}

/// One texel as a degenerate packed interval (its own value, rounded outward): the input of
/// level 0.
pub fn quantize_texels(example: &NormalExample) -> Vec<[u32; 2]> {
    example
        .texels()
        .iter()
        .map(|n| {
            [
                quantize(n.x, false) | quantize(n.y, false) << 16,
                quantize(n.x, true) | quantize(n.y, true) << 16,
            ]
        })
        .collect()
}

/// Union of two packed intervals (per 16-bit half: min of minima, max of maxima). Twin of
/// `range_union` in `glint_range_level.comp`.
pub fn union(a: [u32; 2], b: [u32; 2]) -> [u32; 2] {
    let lo = |v: u32| (v & 0xFFFF, v >> 16);
    let (ax, ay) = lo(a[0]);
    let (bx, by) = lo(b[0]);
    let (cx, cy) = lo(a[1]);
    let (dx, dy) = lo(b[1]);
    [ax.min(bx) | ay.min(by) << 16, cx.max(dx) | cy.max(dy) << 16]
}

/// Dequantized interval of a packed entry (`None` for [`EMPTY`]).
pub fn unpack(e: [u32; 2]) -> Option<NormalInterval> {
    if e == EMPTY {
        return None;
    }
    Some(NormalInterval {
        lo: Vec2::new(dequantize(e[0] & 0xFFFF), dequantize(e[0] >> 16)),
        hi: Vec2::new(dequantize(e[1] & 0xFFFF), dequantize(e[1] >> 16)),
    })
}

/// One level from the one below (`src`: level k − 1, or the quantized texels for level 0):
/// entry (x, y) is the union of the 4 entries of `src` at offsets 0 and `half`, and is
/// [`EMPTY`] when x or y + `span` leaves the example. Twin of one dispatch of the kernel.
pub fn level_from(src: &[[u32; 2]], size: usize, half: usize, span: usize) -> Vec<[u32; 2]> {
    (0..size * size)
        .map(|i| {
            let (x, y) = (i % size, i / size);
            if x + span > size - 1 || y + span > size - 1 {
                return EMPTY;
            }
            let at = |dx: usize, dy: usize| src[(y + dy) * size + x + dx];
            union(
                union(at(0, 0), at(half, 0)),
                union(at(0, half), at(half, half)),
            )
        })
        .collect()
}

/// The sparse table of an example: levels 0..=top, each `size`² packed entries.
#[derive(Clone, Debug, PartialEq)]
pub struct RangeTable {
    size: usize,
    levels: usize,
    entries: Vec<[u32; 2]>,
}

impl RangeTable {
    /// The table of `example` with levels up to edge `patch` (a power of two, the target patch
    /// edge), on the CPU: the reference of the device build.
    pub fn build(example: &NormalExample, patch: u32) -> Self {
        let size = example.size();
        let levels = patch.trailing_zeros() as usize + 1;
        let mut src = quantize_texels(example);
        let mut entries = Vec::with_capacity(levels * size * size);
        for k in 0..levels {
            let half = if k == 0 { 1 } else { 1 << (k - 1) };
            let level = level_from(&src, size, half, 1 << k);
            entries.extend_from_slice(&level);
            src = level;
        }
        RangeTable {
            size,
            levels,
            entries,
        }
    }

    /// A table from entries read back from the device (`levels` levels of `size`²).
    pub fn from_entries(size: usize, levels: usize, entries: Vec<[u32; 2]>) -> Self {
        assert_eq!(
            entries.len(),
            levels * size * size,
            "range table entry count"
        );
        RangeTable {
            size,
            levels,
            entries,
        }
    }

    /// Example edge.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Number of levels (level k has squares of edge 2^k).
    pub fn levels(&self) -> usize {
        self.levels
    }

    /// All packed entries, level by level.
    pub fn entries(&self) -> &[[u32; 2]] {
        &self.entries
    }

    /// Device bytes of the table.
    pub fn bytes(&self) -> u64 {
        (self.entries.len() * 8) as u64
    }

    /// The packed entry of the square [x, x + 2^level]² (one lookup, O(1)).
    pub fn packed(&self, level: usize, x: usize, y: usize) -> [u32; 2] {
        self.entries[(level * self.size + y) * self.size + x]
    }

    /// The interval of n over the example square [x, x + 2^level]²; `None` when the square
    /// leaves the example or the level is not stored.
    pub fn query(&self, level: usize, x: usize, y: usize) -> Option<NormalInterval> {
        if level >= self.levels || x >= self.size || y >= self.size {
            return None;
        }
        unpack(self.packed(level, x, y))
    }
}
