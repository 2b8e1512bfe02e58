// Deterministic per-pixel random numbers: a 32-bit LCG whose output goes through the PCG
// RXS-M-XS permutation (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering"). The seed,
// the pixel and the sample index select the stream, so the same seed renders the same image
// whatever the dispatch order. CPU twin: renderer/src/shading/reference/rng.rs.
#ifndef LAZYSOLID_RENDER_RNG_GLSL
#define LAZYSOLID_RENDER_RNG_GLSL

// The RXS-M-XS output permutation of one LCG state.
uint rng_permute(uint state) {
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// One LCG step.
uint rng_step(uint state) {
    return state * 747796405u + 2891336453u;
}

// A well-mixed 32-bit hash of one word.
uint rng_hash(uint v) {
    return rng_permute(rng_step(v));
}

// Initial state of the stream of (pixel, sample_index) for a render seed.
uint rng_init(uvec2 pixel, uint sample_index, uint seed) {
    return rng_hash(pixel.x ^ rng_hash(pixel.y ^ rng_hash(sample_index ^ rng_hash(seed))));
}

// A uniform float in [0, 1): the top 24 bits of the next output, exactly representable.
float rng_next(inout uint state) {
    state = rng_step(state);
    return float(rng_permute(state) >> 8u) * (1.0 / 16777216.0);
}

// Two successive numbers of the stream, x first.
vec2 rng_next2(inout uint state) {
    float x = rng_next(state);
    float y = rng_next(state);
    return vec2(x, y);
}

#endif
