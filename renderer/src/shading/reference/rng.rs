//! Per-pixel random numbers (twin of `render/rng.glsl`): an LCG stream whose output goes
//! through the PCG RXS-M-XS permutation, seeded by hashing seed, sample index and pixel.

const LCG_MUL: u32 = 747_796_405;
const LCG_ADD: u32 = 2_891_336_453;

fn permute(state: u32) -> u32 {
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

fn step(state: u32) -> u32 {
    state.wrapping_mul(LCG_MUL).wrapping_add(LCG_ADD)
}

/// A well-mixed 32-bit hash of one word (twin of `rng_hash`).
pub fn rng_hash(v: u32) -> u32 {
    permute(step(v))
}

/// Initial state of the stream of `(pixel, sample_index)` under the render `seed`.
pub fn rng_init(pixel: [u32; 2], sample_index: u32, seed: u32) -> u32 {
    rng_hash(pixel[0] ^ rng_hash(pixel[1] ^ rng_hash(sample_index ^ rng_hash(seed))))
}

/// Next uniform float in [0, 1) (24 random bits).
pub fn rng_next(state: &mut u32) -> f32 {
    *state = step(*state);
    (permute(*state) >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Next two floats, x first.
pub fn rng_next2(state: &mut u32) -> glam::Vec2 {
    let x = rng_next(state);
    glam::Vec2::new(x, rng_next(state))
}
