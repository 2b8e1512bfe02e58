//! Exemplar coordinates as the synthesizer stores them: one `u32` per pixel, x in the low and
//! y in the high 16 bits (exemplars are at most 512 pixels wide, see `exemplar.rs`).

/// Packs exemplar coordinate (`x`, `y`).
pub fn pack(x: u32, y: u32) -> u32 {
    x | (y << 16)
}

/// Unpacks a coordinate packed by [`pack`].
pub fn unpack(c: u32) -> (u32, u32) {
    (c & 0xffff, c >> 16)
}

/// Toroidal Chebyshev distance of exemplar pixels `a` and `b` on a `w`×`h` exemplar: how far
/// apart two places of a tiling exemplar are, which both the similarity sets (their spread)
/// and the period repetition (its tolerance) measure.
pub(crate) fn torus_distance(a: (u32, u32), b: (u32, u32), w: u32, h: u32) -> u32 {
    let axis = |p: u32, q: u32, n: u32| {
        let d = p.abs_diff(q);
        d.min(n - d)
    };
    axis(a.0, b.0, w).max(axis(a.1, b.1, h))
}
