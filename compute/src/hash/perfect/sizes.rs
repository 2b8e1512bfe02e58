//! Table sizes of a perfect spatial hash: |H| from the key count, |Φ| from a bits-per-key
//! target, grown geometrically while keeping (h0, h1) injective on the universe.

use super::super::error::HashError;
use super::super::keys::Universe;

/// Offset-table entries per key of the first attempt: σ = 1/(2d), i.e. 4 bits per key with
/// 8-bit offset components (Lefebvre and Hoppe report about 4 bits per key).
pub fn initial_sigma(dimensions: u32) -> f64 {
    1.0 / (2.0 * dimensions as f64)
}

/// Factor by which each failed attempt multiplies the number of Φ entries (at least one more
/// entry per axis).
pub const GROWTH: f64 = 1.1;

/// The sizes of one attempt: |H| and |Φ| per axis and the width of an offset component.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PerfectSizes {
    /// 2 or 3.
    pub dimensions: u32,
    /// |H|: hash-table extent per axis; |H|^d slots.
    pub h: u32,
    /// |Φ|: offset-table extent per axis; |Φ|^d entries, coprime with |H|.
    pub phi: u32,
    /// Bits of one offset component: 8 while |H| ≤ 256, else 16.
    pub component_bits: u32,
}

/// Greatest common divisor.
pub fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

fn pow(x: u32, d: u32) -> u64 {
    (x as u64).pow(d)
}

/// Smallest x with x^d ≥ n.
fn root_ceil(n: u64, d: u32) -> u32 {
    let mut x = (n as f64).powf(1.0 / d as f64).floor().max(1.0) as u32;
    while pow(x, d) < n {
        x += 1;
    }
    while x > 1 && pow(x - 1, d) >= n {
        x -= 1;
    }
    x
}

impl PerfectSizes {
    /// The first attempt for `n` keys of `universe`: |H| the smallest extent with |H|^d ≥ n,
    /// |Φ|^d ≈ σ·n (or `phi` when given), then made valid by [`PerfectSizes::valid_phi`].
    ///
    /// # Errors
    /// More slots or entries than a `u32` index can address.
    pub fn initial(n: usize, universe: &Universe, phi: Option<u32>) -> Result<Self, HashError> {
        let d = universe.dimensions;
        if n == 0 {
            // Nothing to place: one slot, one empty offset entry.
            return Ok(PerfectSizes {
                dimensions: d,
                h: 1,
                phi: 1,
                component_bits: 8,
            });
        }
        let h = root_ceil(n as u64, d);
        if pow(h, d) > crate::prims::MAX_ELEMENTS as u64 || h > 65_536 {
            return Err(HashError::InvalidArgument(format!(
                "{n} keys need {}^{d} hash slots, above the limit of {} slots",
                h,
                crate::prims::MAX_ELEMENTS
            )));
        }
        let target = phi
            .unwrap_or_else(|| root_ceil(((n as f64 * initial_sigma(d)).ceil() as u64).max(1), d));
        Self::with_phi(universe, h, target)
    }

    /// Sizes with |H| = `h` and the smallest valid |Φ| ≥ `phi`.
    fn with_phi(universe: &Universe, h: u32, phi: u32) -> Result<Self, HashError> {
        let d = universe.dimensions;
        let phi = Self::valid_phi(universe, h, phi.max(1));
        if pow(phi, d) > crate::prims::MAX_ELEMENTS as u64 {
            return Err(HashError::InvalidArgument(format!(
                "an offset table of {phi}^{d} entries is above the limit of {} entries",
                crate::prims::MAX_ELEMENTS
            )));
        }
        Ok(PerfectSizes {
            dimensions: d,
            h,
            phi,
            component_bits: if h <= 256 { 8 } else { 16 },
        })
    }

    /// The smallest |Φ| ≥ `phi` with gcd(|Φ|, |H|) = 1 and |U| ≤ |H|·|Φ| along every axis: by
    /// the Chinese remainder theorem (p mod |H|, p mod |Φ|) then identifies p, so the hash
    /// is injective on the universe before any offset is chosen.
    pub fn valid_phi(universe: &Universe, h: u32, phi: u32) -> u32 {
        let extent = universe.dims[..universe.dimensions as usize]
            .iter()
            .copied()
            .max()
            .unwrap_or(1);
        let mut phi = phi.max(extent.div_ceil(h));
        while gcd(phi, h) != 1 {
            phi += 1;
        }
        phi
    }

    /// The next attempt after a failure: |Φ|^d grown by [`GROWTH`] (at least +1 per axis).
    pub fn grown(&self, universe: &Universe) -> Result<Self, HashError> {
        let scaled = (self.phi as f64 * GROWTH.powf(1.0 / self.dimensions as f64)).ceil() as u32;
        Self::with_phi(universe, self.h, scaled.max(self.phi + 1))
    }

    /// Hash-table slots: |H|^d.
    pub fn slots(&self) -> u32 {
        pow(self.h, self.dimensions) as u32
    }

    /// Offset-table entries: |Φ|^d.
    pub fn entries(&self) -> u32 {
        pow(self.phi, self.dimensions) as u32
    }

    /// Bits of one packed offset entry: d components.
    pub fn entry_bits(&self) -> u32 {
        self.dimensions * self.component_bits
    }

    /// 32-bit words of the packed offset table, with two words of padding so a lookup may
    /// always read three consecutive words.
    pub fn offset_words(&self) -> usize {
        (self.entries() as u64 * self.entry_bits() as u64).div_ceil(32) as usize + 2
    }

    /// Offset-table bits per key for `n` keys (the paper's overhead measure, padding excluded).
    pub fn bits_per_key(&self, n: usize) -> f64 {
        self.entries() as f64 * self.entry_bits() as f64 / n.max(1) as f64
    }

    /// Keys per slot for `n` keys.
    pub fn load_factor(&self, n: usize) -> f64 {
        n as f64 / self.slots() as f64
    }

    /// E.g. `|H| = 126^3, |Φ| = 71^3 (8-bit components)`.
    pub fn describe(&self) -> String {
        let d = self.dimensions;
        format!(
            "|H| = {}^{d}, |Φ| = {}^{d} ({}-bit components)",
            self.h, self.phi, self.component_bits
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::KeyLayout;

    #[test]
    fn sizes_follow_the_rules() {
        let u = Universe::new_3d([512; 3], KeyLayout::Morton).unwrap();
        let s = PerfectSizes::initial(2_000_000, &u, None).unwrap();
        assert_eq!(s.h, 126);
        assert!(pow(125, 3) < 2_000_000 && pow(126, 3) >= 2_000_000);
        assert_eq!(gcd(s.h, s.phi), 1);
        assert!(s.h as u64 * s.phi as u64 >= 512);
        assert!((s.bits_per_key(2_000_000) - 4.0).abs() < 0.3, "{s:?}");
        let g = s.grown(&u).unwrap();
        assert!(g.phi > s.phi && gcd(g.h, g.phi) == 1);
        let u2 = Universe::new_2d(4096, 4096, KeyLayout::RowMajor).unwrap();
        let s2 = PerfectSizes::initial(100_000, &u2, None).unwrap();
        assert_eq!((s2.h, s2.component_bits), (317, 16));
        assert!(s2.h * s2.phi >= 4096);
    }
}
