//! Key universes: 2D and 3D grids whose points become integer keys by a layout.

use super::error::HashError;

/// How grid points become integer keys. Coherent probing keeps neighbouring keys neighbours,
/// so the layout decides how much of the data's coherence reaches memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum KeyLayout {
    /// x + W·y (+ W·H·z): rows are contiguous.
    RowMajor,
    /// Bit interleaving of the coordinates (Z-order) over the power-of-two cube around the grid.
    Morton,
    /// Morton with its bits reversed: neighbours land far apart (no coherence at all).
    BitReversedMorton,
}

impl KeyLayout {
    /// All layouts, for benchmarks and tests.
    pub const ALL: [KeyLayout; 3] = [
        KeyLayout::RowMajor,
        KeyLayout::Morton,
        KeyLayout::BitReversedMorton,
    ];

    /// Short name for tables and file names.
    pub fn name(self) -> &'static str {
        match self {
            KeyLayout::RowMajor => "row-major",
            KeyLayout::Morton => "morton",
            KeyLayout::BitReversedMorton => "bit-reversed",
        }
    }
}

/// A 2D or 3D grid of possible keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Universe {
    /// Extent along x, y, z (z = 1 for 2D).
    pub dims: [u32; 3],
    /// 2 or 3.
    pub dimensions: u32,
    /// The key layout.
    pub layout: KeyLayout,
}

/// Largest extent along one axis: 3D Morton keys of 2048³ take 33 bits.
pub const MAX_EXTENT: u32 = 1 << 16;

impl Universe {
    /// A 2D universe of `width` × `height` points.
    pub fn new_2d(width: u32, height: u32, layout: KeyLayout) -> Result<Universe, HashError> {
        Self::new([width, height, 1], 2, layout)
    }

    /// A 3D universe of `x` × `y` × `z` points.
    pub fn new_3d(dims: [u32; 3], layout: KeyLayout) -> Result<Universe, HashError> {
        Self::new(dims, 3, layout)
    }

    fn new(dims: [u32; 3], dimensions: u32, layout: KeyLayout) -> Result<Universe, HashError> {
        if dims.iter().any(|&d| d == 0 || d > MAX_EXTENT) {
            return Err(HashError::InvalidArgument(format!(
                "universe extents {dims:?} must lie in 1..={MAX_EXTENT}"
            )));
        }
        let u = Universe {
            dims,
            dimensions,
            layout,
        };
        if u.key_count() > 1 << 58 {
            return Err(HashError::InvalidArgument(format!(
                "universe {} has more than 2^58 keys",
                u.describe()
            )));
        }
        Ok(u)
    }

    /// Bits per axis of the power-of-two cube that Morton layouts use.
    pub fn axis_bits(&self) -> u32 {
        let largest = self
            .dims
            .iter()
            .take(self.dimensions as usize)
            .copied()
            .max()
            .unwrap_or(1);
        largest.next_power_of_two().trailing_zeros()
    }

    /// Number of distinct key values: keys lie in `0 .. key_count()`.
    pub fn key_count(&self) -> u64 {
        match self.layout {
            KeyLayout::RowMajor => self.dims.iter().map(|&d| d as u64).product(),
            _ => 1u64 << (self.axis_bits() * self.dimensions),
        }
    }

    /// Bits of `key + 1`, the key field of a cell (0 marks an empty cell).
    pub fn key_bits(&self) -> u32 {
        64 - self.key_count().leading_zeros()
    }

    /// Whether `p` lies in the grid.
    pub fn contains(&self, p: [u32; 3]) -> bool {
        (0..3).all(|a| p[a] < self.dims[a])
    }

    /// The key of grid point `p` (z ignored in 2D).
    pub fn key(&self, p: [u32; 3]) -> u64 {
        let [x, y, z] = p;
        match self.layout {
            KeyLayout::RowMajor => {
                x as u64 + self.dims[0] as u64 * (y as u64 + self.dims[1] as u64 * z as u64)
            }
            KeyLayout::Morton => morton_encode(p, self.dimensions),
            KeyLayout::BitReversedMorton => {
                let bits = self.axis_bits() * self.dimensions;
                if bits == 0 {
                    0
                } else {
                    morton_encode(p, self.dimensions).reverse_bits() >> (64 - bits)
                }
            }
        }
    }

    /// The grid point of `key` (inverse of [`Universe::key`]).
    pub fn point(&self, key: u64) -> [u32; 3] {
        match self.layout {
            KeyLayout::RowMajor => {
                let w = self.dims[0] as u64;
                let h = self.dims[1] as u64;
                [
                    (key % w) as u32,
                    ((key / w) % h) as u32,
                    (key / (w * h)) as u32,
                ]
            }
            KeyLayout::Morton => morton_decode(key, self.dimensions),
            KeyLayout::BitReversedMorton => {
                let bits = self.axis_bits() * self.dimensions;
                let m = if bits == 0 {
                    0
                } else {
                    key.reverse_bits() >> (64 - bits)
                };
                morton_decode(m, self.dimensions)
            }
        }
    }

    /// E.g. `2D 4096x4096 morton`.
    pub fn describe(&self) -> String {
        if self.dimensions == 2 {
            format!(
                "2D {}x{} {}",
                self.dims[0],
                self.dims[1],
                self.layout.name()
            )
        } else {
            format!(
                "3D {}x{}x{} {}",
                self.dims[0],
                self.dims[1],
                self.dims[2],
                self.layout.name()
            )
        }
    }
}

fn spread(v: u32, dimensions: u32) -> u64 {
    let mut out = 0u64;
    for bit in 0..(64 / dimensions).min(32) {
        out |= (((v >> bit) & 1) as u64) << (bit * dimensions);
    }
    out
}

fn compact(m: u64, dimensions: u32) -> u32 {
    let mut out = 0u32;
    for bit in 0..(64 / dimensions).min(32) {
        out |= (((m >> (bit * dimensions)) & 1) as u32) << bit;
    }
    out
}

/// Interleaves the bits of the first `dimensions` coordinates: x in bit 0.
pub fn morton_encode(p: [u32; 3], dimensions: u32) -> u64 {
    (0..dimensions as usize)
        .map(|a| spread(p[a], dimensions) << a)
        .fold(0, |acc, v| acc | v)
}

/// Inverse of [`morton_encode`].
pub fn morton_decode(m: u64, dimensions: u32) -> [u32; 3] {
    let mut p = [0u32; 3];
    for (a, c) in p.iter_mut().enumerate().take(dimensions as usize) {
        *c = compact(m >> a, dimensions);
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_round_trip_and_fit_the_key_count() {
        for layout in KeyLayout::ALL {
            for u in [
                Universe::new_2d(13, 7, layout).unwrap(),
                Universe::new_3d([5, 9, 3], layout).unwrap(),
            ] {
                let mut seen = std::collections::HashSet::new();
                for z in 0..u.dims[2] {
                    for y in 0..u.dims[1] {
                        for x in 0..u.dims[0] {
                            let k = u.key([x, y, z]);
                            assert!(k < u.key_count(), "{u:?} {k}");
                            assert_eq!(u.point(k), [x, y, z]);
                            assert!(seen.insert(k));
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn morton_of_2048_cubed_needs_33_bits() {
        let u = Universe::new_3d([2048; 3], KeyLayout::Morton).unwrap();
        assert_eq!(u.key_count(), 1 << 33);
        assert_eq!(u.key_bits(), 34);
        assert_eq!(u.key([2047; 3]), (1 << 33) - 1);
        assert_eq!(morton_encode([1, 0, 0], 3), 1);
        assert_eq!(morton_encode([0, 1, 0], 3), 2);
        assert_eq!(morton_encode([0, 0, 1], 3), 4);
    }
}
