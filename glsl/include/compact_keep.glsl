// Which words stream compaction keeps, read by segments (see segments.glsl): where the flag is
// not 0 (COMPACT_BY_FLAGS), or where the value differs from the sentinel (COMPACT_BY_SENTINEL).
#ifndef LAZYSOLID_COMPACT_KEEP_GLSL
#define LAZYSOLID_COMPACT_KEEP_GLSL

#include "segments.glsl"

layout(binding = 1, scalar) readonly buffer Flags { uvec4 flags[]; };

// Quad q of the values and whether each of its words is kept (false past n).
bvec4 kept(uint q, uint n, uint mode, uint sentinel, out uvec4 values) {
    values = src[q];
    bvec4 keep = mode == COMPACT_BY_FLAGS ? notEqual(flags[q], uvec4(0u)) : notEqual(values, uvec4(sentinel));
    uint w = 4u * q;
    return bvec4(keep.x && w < n, keep.y && w + 1u < n, keep.z && w + 2u < n, keep.w && w + 3u < n);
}

#endif
