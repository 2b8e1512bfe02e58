//! Exemplar coordinates as the synthesizer stores them: one `u32` per pixel, x in the low and
//! y in the high 16 bits (exemplars are at most 256 pixels wide, see `exemplar.rs`).

/// Packs exemplar coordinate (`x`, `y`).
pub fn pack(x: u32, y: u32) -> u32 {
    x | (y << 16)
}

/// Unpacks a coordinate packed by [`pack`].
pub fn unpack(c: u32) -> (u32, u32) {
    (c & 0xffff, c >> 16)
}
