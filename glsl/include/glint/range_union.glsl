// Packed 16-bit intervals of (n_x, n_y) (renderer/src/glint/range_table.rs): entries are
// (min n_x | min n_y << 16, max n_x | max n_y << 16), n in [-1, 1] mapped to [0, 65535],
// minima rounded down and maxima up.
#ifndef LAZYSOLID_GLINT_RANGE_UNION_GLSL
#define LAZYSOLID_GLINT_RANGE_UNION_GLSL

// An entry that contains nothing (the union's identity): `EMPTY` in range_table.rs.
const uvec2 GLINT_RANGE_EMPTY = uvec2(0xFFFFFFFFu, 0u);

// Union of two packed intervals: per 16-bit half, the min of the minima and the max of the
// maxima. Twin of `range_table::union`.
uvec2 range_union(uvec2 a, uvec2 b) {
    uint lo = min(a.x & 0xFFFFu, b.x & 0xFFFFu) | (min(a.x >> 16u, b.x >> 16u) << 16u);
    uint hi = max(a.y & 0xFFFFu, b.y & 0xFFFFu) | (max(a.y >> 16u, b.y >> 16u) << 16u);
    return uvec2(lo, hi);
}

#endif
