// Loading one scan/reduce tile: SCAN_TILE consecutive u32 words, SCAN_ITEMS_PER_THREAD of them
// owned by each invocation (contiguous, so the serial part of a scan runs over them in order).
// Full tiles are read as uvec4; the last, partial tile word by word with zeros past the end.
#ifndef LAZYSOLID_SCAN_TILE_GLSL
#define LAZYSOLID_SCAN_TILE_GLSL

#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

#define SCAN_VEC4_PER_THREAD (SCAN_ITEMS_PER_THREAD / 4)

// Reads the words [first, first + SCAN_ITEMS_PER_THREAD) of `src` into `v`, `fill` past `n`.
void load_items(uint64_t src, uint first, uint n, uint fill, out uint v[SCAN_ITEMS_PER_THREAD]) {
    if (first + SCAN_ITEMS_PER_THREAD <= n) {
        UVec4Ptr p = UVec4Ptr(src);
        for (uint j = 0; j < SCAN_VEC4_PER_THREAD; ++j) {
            uvec4 q = p.v[first / 4 + j];
            v[4 * j + 0] = q.x;
            v[4 * j + 1] = q.y;
            v[4 * j + 2] = q.z;
            v[4 * j + 3] = q.w;
        }
    } else {
        U32Ptr p = U32Ptr(src);
        for (uint j = 0; j < SCAN_ITEMS_PER_THREAD; ++j) {
            v[j] = first + j < n ? p.v[first + j] : fill;
        }
    }
}

#endif
