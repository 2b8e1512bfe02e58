//! The two baselines of the range table ([`super::range_table`]) in `lazysolid bench glints`,
//! with the same answers: the packed 16-bit interval (floor for minima, ceil for maxima) of n
//! over the example square [x, x + 2^k]², i.e. the union of its (2^k + 1)² quantized texels.
//!
//! - [`MinMaxMip`]: a min–max mip hierarchy. Level m holds the interval of every **aligned**
//!   2^m × 2^m block of texels ((n / 2^m)² entries, 4/3 · n² in all, level 0 being the quantized
//!   texels). An unaligned square is the union of its maximal aligned blocks: the product of
//!   the two axes' canonical dyadic decompositions (at most 2 · log2(2^k + 1) + 1 intervals per
//!   axis), each rectangle of sizes 2^i × 2^j cut into 2^|i − j| squares of the smaller size.
//!   That is exact, and it is the fewest aligned squares that cover the query. It is **not**
//!   O(log n): a square whose first column is odd has that whole column as single texels, so
//!   the count grows with the edge (about 3.9 · 2^k blocks on average over random starts). The
//!   paper's "O(log n)" holds for one axis; aligned squares cannot cover an unaligned one with
//!   fewer (aligned squares nest or are disjoint, so a cover needs one per maximal block).
//! - [`brute_force`]: every texel of the square, (2^k + 1)² reads.
//!
//! [`random_squares`] makes the query batches the bench and the tests share; the device
//! twins of the builds and queries are in [`super::gpu_range_query`].

use super::example::NormalExample;
use super::range_table::{quantize_texels, union, RangeTable, EMPTY};
use rand::{Rng, SeedableRng};

/// One range query: the example square [x, x + 2^level]² (both ends inclusive in texels).
#[derive(Clone, Copy, Debug, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct RangeSquare {
    /// First column.
    pub x: u32,
    /// First row.
    pub y: u32,
    /// The square's edge is 2^level texel steps ((2^level + 1)² texels).
    pub level: u32,
}

/// `count` squares of the example of edge `size`, with levels uniform in 0..`levels` and
/// starts uniform among those whose square stays in the example (x + 2^level ≤ size − 1),
/// from `seed` (a fixed seed gives the same batch on every run and machine).
///
/// # Panics
/// When a level's square does not fit in the example (2^(levels − 1) ≥ size).
pub fn random_squares(size: usize, levels: usize, count: usize, seed: u64) -> Vec<RangeSquare> {
    assert!(
        levels >= 1 && (1usize << (levels - 1)) < size,
        "{levels} levels do not fit an example of edge {size}"
    );
    let mut r = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            let level = r.random_range(0..levels as u32);
            let last = (size - 1 - (1usize << level)) as u32;
            RangeSquare {
                x: r.random_range(0..=last),
                y: r.random_range(0..=last),
                level,
            }
        })
        .collect()
}

/// The answer of the sparse table: one lookup.
pub fn table_query(table: &RangeTable, q: RangeSquare) -> [u32; 2] {
    table.packed(q.level as usize, q.x as usize, q.y as usize)
}

/// The union of every quantized texel of the square (`texels`: [`quantize_texels`] of an
/// example of edge `size`). Twin of the brute-force mode of `glint_range_query.comp`.
pub fn brute_force(texels: &[[u32; 2]], size: usize, q: RangeSquare) -> [u32; 2] {
    let span = 1usize << q.level;
    let (x0, y0) = (q.x as usize, q.y as usize);
    let mut acc = EMPTY;
    for y in y0..=y0 + span {
        for &t in &texels[y * size + x0..=y * size + x0 + span] {
            acc = union(acc, t);
        }
    }
    acc
}

/// Most pieces of a [`dyadic_pieces`] decomposition of a range inside a u32 (two per bit).
const MAX_PIECES: usize = 64;

/// The canonical dyadic decomposition of the texels [start, end) into `out`: the maximal
/// aligned intervals inside it, as (first texel, log2 of the length), left to right (greedy:
/// the largest aligned interval that starts at the current texel and fits); returns their
/// count. Twin of the loop in `glint_range_query.comp`.
fn dyadic_pieces_into(start: u32, end: u32, out: &mut [(u32, u32); MAX_PIECES]) -> usize {
    let mut count = 0;
    let mut p = start;
    while p < end {
        let align = if p == 0 { 31 } else { p.trailing_zeros() };
        let fits = 31 - (end - p).leading_zeros();
        let lg = align.min(fits);
        out[count] = (p, lg);
        count += 1;
        p += 1 << lg;
    }
    count
}

/// The canonical dyadic decomposition of the texels [start, end): the maximal aligned
/// intervals inside it, as (first texel, log2 of the length), left to right.
pub fn dyadic_pieces(start: u32, end: u32) -> Vec<(u32, u32)> {
    let mut out = [(0, 0); MAX_PIECES];
    let count = dyadic_pieces_into(start, end, &mut out);
    out[..count].to_vec()
}

/// Edge of the mip level `m` of an example of edge `size` (a power of two).
fn level_edge(size: usize, m: usize) -> usize {
    size >> m
}

/// Entry offset of level `m`: Σ_{j<m} (size / 2^j)² = 4 (size² − (size / 2^m)²) / 3.
pub fn mip_level_offset(size: usize, m: usize) -> usize {
    let e = level_edge(size, m);
    4 * (size * size - e * e) / 3
}

/// One mip level from the one below (edge `src_edge`): entry (x, y) is the union of the 2 × 2
/// entries (2x + i, 2y + j). Twin of one dispatch of `glint_minmax_mip.comp`.
pub fn mip_level_from(src: &[[u32; 2]], src_edge: usize) -> Vec<[u32; 2]> {
    let edge = src_edge / 2;
    (0..edge * edge)
        .map(|i| {
            let (x, y) = (2 * (i % edge), 2 * (i / edge));
            let at = |dx: usize, dy: usize| src[(y + dy) * src_edge + x + dx];
            union(union(at(0, 0), at(1, 0)), union(at(0, 1), at(1, 1)))
        })
        .collect()
}

/// The min–max mip hierarchy of an example: levels 0 (the quantized texels) to log2(size)
/// (one entry), level by level in one array.
#[derive(Clone, Debug, PartialEq)]
pub struct MinMaxMip {
    size: usize,
    entries: Vec<[u32; 2]>,
}

impl MinMaxMip {
    /// The hierarchy of `example` on the CPU: the reference of the device build.
    pub fn build(example: &NormalExample) -> Self {
        let size = example.size();
        let mut level = quantize_texels(example);
        let mut entries = Vec::with_capacity(mip_level_offset(size, Self::levels_of(size)));
        for m in 1..Self::levels_of(size) {
            let next = mip_level_from(&level, level_edge(size, m - 1));
            entries.extend_from_slice(&level);
            level = next;
        }
        entries.extend_from_slice(&level);
        MinMaxMip { size, entries }
    }

    fn levels_of(size: usize) -> usize {
        size.trailing_zeros() as usize + 1
    }

    /// A hierarchy from entries read back from the device.
    ///
    /// # Panics
    /// When the count is not that of a full hierarchy of edge `size`.
    pub fn from_entries(size: usize, entries: Vec<[u32; 2]>) -> Self {
        assert_eq!(
            entries.len(),
            Self::entry_count(size),
            "min–max mip entry count"
        );
        MinMaxMip { size, entries }
    }

    /// Entries of the full hierarchy of an example of edge `size` (a power of two).
    pub fn entry_count(size: usize) -> usize {
        mip_level_offset(size, Self::levels_of(size))
    }

    /// Example edge.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Levels: 0 (texels) to log2(size).
    pub fn levels(&self) -> usize {
        Self::levels_of(self.size)
    }

    /// All packed entries, level by level.
    pub fn entries(&self) -> &[[u32; 2]] {
        &self.entries
    }

    /// Bytes of the hierarchy (8 per entry).
    pub fn bytes(&self) -> u64 {
        (self.entries.len() * 8) as u64
    }

    /// The aligned block (bx, by) of level `m`: texels [bx·2^m, (bx + 1)·2^m)².
    pub fn block(&self, m: usize, bx: usize, by: usize) -> [u32; 2] {
        self.entries[mip_level_offset(self.size, m) + by * level_edge(self.size, m) + bx]
    }

    /// The packed interval of the square `q` and the number of blocks it combined: the union
    /// of its maximal aligned blocks (see the module's documentation).
    pub fn query_counted(&self, q: RangeSquare) -> ([u32; 2], usize) {
        let end = |s: u32| s + (1 << q.level) + 1;
        let (mut xs, mut ys) = ([(0, 0); MAX_PIECES], [(0, 0); MAX_PIECES]);
        let cx = dyadic_pieces_into(q.x, end(q.x), &mut xs);
        let cy = dyadic_pieces_into(q.y, end(q.y), &mut ys);
        let mut acc = EMPTY;
        let mut blocks = 0;
        for &(py, j) in &ys[..cy] {
            for &(px, i) in &xs[..cx] {
                let m = i.min(j);
                let edge = level_edge(self.size, m as usize);
                let at = mip_level_offset(self.size, m as usize)
                    + (py >> m) as usize * edge
                    + (px >> m) as usize;
                let stride = if i > j { 1 } else { edge };
                let count = 1usize << i.abs_diff(j);
                for t in 0..count {
                    acc = union(acc, self.entries[at + t * stride]);
                }
                blocks += count;
            }
        }
        (acc, blocks)
    }

    /// The packed interval of the square `q` (exact: equal to [`brute_force`]).
    pub fn query(&self, q: RangeSquare) -> [u32; 2] {
        self.query_counted(q).0
    }
}

/// Bytes of a min–max mip over a map of `edge`² texels (any edge: levels of ⌈edge / 2^m⌉²
/// entries down to one), 8 bytes per entry: the hierarchy an explicit map of that size needs.
pub fn minmax_mip_bytes(edge: u64) -> u64 {
    let mut e = edge;
    let mut entries = e * e;
    while e > 1 {
        e = e.div_ceil(2);
        entries += e * e;
    }
    entries * 8
}
