// Helpers of the perfect-hash construction kernels (compute/src/hash/perfect/gpu.rs); they
// mirror compute/src/hash/perfect/function.rs.
#ifndef LAZYSOLID_HASH_PERFECT_BUILD_GLSL
#define LAZYSOLID_HASH_PERFECT_BUILD_GLSL

// States of a bucket besides "candidates consumed so far".
const uint PERFECT_PLACED = 0xffffffffu;
const uint PERFECT_FAILED = 0xfffffffeu;
// Status words (u64): out-of-universe key + 1 (max), duplicates, smallest duplicate key,
// failed buckets, unconstrained payload equal to HASH_NOT_FOUND, smallest failed bucket.
const uint PERFECT_STATUS_BAD_KEY = 0u;
const uint PERFECT_STATUS_DUPLICATES = 1u;
const uint PERFECT_STATUS_DUPLICATE_KEY = 2u;
const uint PERFECT_STATUS_FAILED = 3u;
const uint PERFECT_STATUS_BAD_PAYLOAD = 4u;
const uint PERFECT_STATUS_FAILED_BUCKET = 5u;

// h0 coordinates packed into one word: 16 bits per axis in 2D, 11 in 3D.
uint perfect_pack_h0(uvec3 c, uint dimensions) {
    return dimensions == 2u ? c.x | (c.y << 16) : c.x | (c.y << 11) | (c.z << 22);
}

uvec3 perfect_unpack_h0(uint w, uint dimensions) {
    return dimensions == 2u ? uvec3(w & 0xffffu, w >> 16, 0u) : uvec3(w & 0x7ffu, (w >> 11) & 0x7ffu, w >> 22);
}

uvec3 perfect_coords(uint s, uint h) {
    uint row = s / h;
    uint z = row / h;
    return uvec3(s - row * h, row - z * h, z);
}

// (a + b) mod h per axis for a, b < h, without a division (a select per axis: integer division
// by a variable is emulated lane by lane on llvmpipe).
uvec3 perfect_add_mod(uvec3 a, uvec3 b, uint h) {
    uvec3 s = a + b;
    return mix(s, s - h, greaterThanEqual(s, uvec3(h)));
}

uint perfect_linear(uvec3 c, uint h) {
    return c.x + h * (c.y + h * c.z);
}

// The claim of bucket q (m keys) in an iteration: later iterations first, then larger buckets
// (sizes above 63 tie), then smaller bucket ids.
uint64_t perfect_stamp(uint iteration, uint m, uint q) {
    return (uint64_t(iteration) << 38) | (uint64_t(min(m, 63u)) << 32) | uint64_t(~q);
}

// search_start in function.rs.
uint perfect_search_start(uint q, uint slots) {
    uint x = q ^ 0x9e3779b9u;
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return uint((uint64_t(x) * uint64_t(slots)) >> 32);
}

#endif
