// Universe keys back to grid points, as compute/src/hash/keys.rs (Universe::point) does:
// layout 0 row-major, 1 Morton, 2 bit-reversed Morton.
#ifndef LAZYSOLID_HASH_PERFECT_KEYS_GLSL
#define LAZYSOLID_HASH_PERFECT_KEYS_GLSL

#include "morton.glsl"

uint perfect_compact2(uint64_t m) {
    m &= 0x5555555555555555ul;
    m = (m | (m >> 1)) & 0x3333333333333333ul;
    m = (m | (m >> 2)) & 0x0f0f0f0f0f0f0f0ful;
    m = (m | (m >> 4)) & 0x00ff00ff00ff00fful;
    m = (m | (m >> 8)) & 0x0000ffff0000fffful;
    m = (m | (m >> 16)) & 0x00000000fffffffful;
    return uint(m);
}

uvec3 perfect_morton_decode(uint64_t m, uint dimensions) {
    if (dimensions == 2u) {
        return uvec3(perfect_compact2(m), perfect_compact2(m >> 1), 0u);
    }
    return morton3_decode(m);
}

// The point of `key`; false when the key lies outside the universe.
bool perfect_key_point(uint64_t key, uint layout_id, uvec3 dims, uint dimensions, uint axis_bits, uint64_t key_count, out uvec3 p) {
    p = uvec3(0u);
    if (key >= key_count) {
        return false;
    }
    if (layout_id == 0u) {
        uint64_t w = uint64_t(dims.x);
        uint64_t h = uint64_t(dims.y);
        p = uvec3(uint(key % w), uint((key / w) % h), uint(key / (w * h)));
    } else if (layout_id == 1u) {
        p = perfect_morton_decode(key, dimensions);
    } else {
        uint bits = axis_bits * dimensions;
        uint64_t r = (uint64_t(bitfieldReverse(uint(key))) << 32) | uint64_t(bitfieldReverse(uint(key >> 32)));
        p = perfect_morton_decode(bits == 0u ? 0ul : r >> (64u - bits), dimensions);
    }
    if (dimensions == 2u) {
        p.z = 0u;
    }
    return all(lessThan(p, dims));
}

#endif
