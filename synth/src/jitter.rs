//! The jitter of Lefebvre & Hoppe 2005, in integers: `J_l(p) = ⌊h_l · H(p) · r_l + ½⌋` with
//! `H` a hash of the absolute output position, the level and the seed into [−1, 1)², computed
//! identically by `glsl/include/synth/synth.glsl`. Depending on absolute positions only is what
//! makes every window of the plane deterministic.

use super::params::JITTER_ONE;

fn mix(mut h: u32) -> u32 {
    h ^= h >> 16;
    h = h.wrapping_mul(0x7feb_352d);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846c_a68b);
    h ^= h >> 16;
    h
}

/// A well-mixed hash of four words.
pub fn hash4(a: u32, b: u32, c: u32, d: u32) -> u32 {
    let mut h = mix(a ^ 0x9e37_79b9);
    h = mix(h ^ b);
    h = mix(h ^ c);
    mix(h ^ d)
}

/// The jitter offset of absolute position (`x`, `y`) at `level` with spacing `spacing` and
/// quantized strength `strength` (in 1/[`JITTER_ONE`] steps). Each component lies in
/// `-spacing..=spacing`.
pub fn jitter(x: i32, y: i32, level: u32, seed: u32, spacing: u32, strength: u32) -> [i32; 2] {
    const _: () = assert!(JITTER_ONE == 1 << 8);
    [0u32, 1].map(|axis| {
        let h = hash4(x as u32, y as u32, level | (axis << 8), seed);
        let v = (h >> 16) as i64 - 32768;
        ((spacing as i64 * v * strength as i64 + (1 << 22)) >> 23) as i32
    })
}
