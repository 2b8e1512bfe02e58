//! The hash function h(p) = h0(p) + Φ[h1(p)] mod |H| with M0 = M1 = identity, and the packed
//! offset table, exactly as `glsl/include/hash/perfect.glsl` evaluates them.

use super::sizes::PerfectSizes;

/// h0(p) = p mod |H| per axis (z = 0 in 2D).
pub fn h0(sizes: &PerfectSizes, p: [u32; 3]) -> [u32; 3] {
    p.map(|c| c % sizes.h)
}

/// h1(p) = p mod |Φ| per axis, as a linear index x + |Φ|·(y + |Φ|·z) into Φ.
pub fn bucket(sizes: &PerfectSizes, p: [u32; 3]) -> u32 {
    let f = sizes.phi;
    (p[0] % f) + f * ((p[1] % f) + f * (p[2] % f))
}

/// Linear slot x + |H|·(y + |H|·z) of slot coordinates.
pub fn slot_index(sizes: &PerfectSizes, c: [u32; 3]) -> u32 {
    c[0] + sizes.h * (c[1] + sizes.h * c[2])
}

/// Slot coordinates of a linear slot or offset index (inverse of [`slot_index`]).
pub fn slot_coords(sizes: &PerfectSizes, s: u32) -> [u32; 3] {
    let h = sizes.h;
    [s % h, (s / h) % h, s / (h * h)]
}

/// (a + b) mod |H| per axis, for a, b < |H|.
pub fn add_mod(sizes: &PerfectSizes, a: [u32; 3], b: [u32; 3]) -> [u32; 3] {
    std::array::from_fn(|i| {
        let s = a[i] + b[i];
        if s >= sizes.h {
            s - sizes.h
        } else {
            s
        }
    })
}

/// Packs per-entry offsets (linear offset indices, see [`slot_coords`]) into the table's words:
/// entry q occupies bits q·E .. q·E + E (E = d × component bits), components x first, each
/// in `component_bits` bits, words little-endian; two zero words of padding follow.
pub fn pack_offsets(sizes: &PerfectSizes, offsets: &[u32]) -> Vec<u32> {
    let mut words = vec![0u32; sizes.offset_words()];
    let e = sizes.entry_bits() as u64;
    for (q, &o) in offsets.iter().enumerate() {
        let value = entry_value(sizes, slot_coords(sizes, o));
        let bit = q as u64 * e;
        let (w, s) = ((bit / 32) as usize, bit % 32);
        let wide = (value as u128) << s;
        for k in 0..3 {
            words[w + k] |= (wide >> (32 * k)) as u32;
        }
    }
    words
}

/// The E-bit value of an offset vector.
fn entry_value(sizes: &PerfectSizes, o: [u32; 3]) -> u64 {
    let c = sizes.component_bits;
    (0..sizes.dimensions as usize).fold(0u64, |v, a| v | (o[a] as u64) << (a as u32 * c))
}

/// Φ\[q\] as an offset vector, read from the packed words like the GLSL lookup.
pub fn read_offset(sizes: &PerfectSizes, words: &[u32], q: u32) -> [u32; 3] {
    let bit = q as u64 * sizes.entry_bits() as u64;
    let (w, s) = ((bit / 32) as usize, bit % 32);
    let wide = words[w] as u128 | (words[w + 1] as u128) << 32 | (words[w + 2] as u128) << 64;
    let v = (wide >> s) as u64;
    let c = sizes.component_bits;
    let mask = (1u64 << c) - 1;
    std::array::from_fn(|a| {
        if a < sizes.dimensions as usize {
            ((v >> (a as u32 * c)) & mask) as u32
        } else {
            0
        }
    })
}

/// The slot of point `p`: h0(p) + Φ[h1(p)] mod |H|, linear.
pub fn slot(sizes: &PerfectSizes, words: &[u32], p: [u32; 3]) -> u32 {
    let o = read_offset(sizes, words, bucket(sizes, p));
    slot_index(sizes, add_mod(sizes, h0(sizes, p), o))
}

/// Where a bucket's search for an offset starts: a hashed slot, so equal-sized buckets do not
/// all crowd the same part of the table (lowbias32 of q, scaled onto the slots).
pub fn search_start(q: u32, slots: u32) -> u32 {
    let mut x = q ^ 0x9e37_79b9;
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    ((x as u64 * slots as u64) >> 32) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_round_trips_for_every_width() {
        for (dimensions, h) in [(2, 200), (2, 300), (3, 100), (3, 300)] {
            let sizes = PerfectSizes {
                dimensions,
                h,
                phi: 7,
                component_bits: if h <= 256 { 8 } else { 16 },
            };
            let n = sizes.entries() as usize;
            let slots = sizes.slots();
            let offsets: Vec<u32> = (0..n as u32).map(|q| search_start(q, slots)).collect();
            let words = pack_offsets(&sizes, &offsets);
            for (q, &o) in offsets.iter().enumerate() {
                assert_eq!(
                    read_offset(&sizes, &words, q as u32),
                    slot_coords(&sizes, o)
                );
            }
        }
    }
}
