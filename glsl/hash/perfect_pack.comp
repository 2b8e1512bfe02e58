#version 460
// Perfect-hash construction, final part 1 (one invocation per offset entry): the entry's
// offset (a linear index over H) packed into the table's words with atomicOr (entries share
// words; OR commutes, so the result does not depend on the order).
#include "common.glsl"
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t offsets;
    uint64_t words;
    uint entries;
    uint h;
    uint dimensions;
    uint component_bits;
} pc;

void main() {
    uint q = uint(global_index());
    if (q >= pc.entries) {
        return;
    }
    uvec3 o = perfect_coords(U32Ptr(pc.offsets).v[q], pc.h);
    uint c = pc.component_bits;
    uint64_t v = uint64_t(o.x) | (uint64_t(o.y) << c) | (pc.dimensions == 3u ? uint64_t(o.z) << (2u * c) : 0ul);
    if (v == 0ul) {
        return;
    }
    uint e = pc.dimensions * c;
    uint64_t bit = uint64_t(q) * uint64_t(e);
    uint w = uint(bit >> 5);
    uint s = uint(bit & 31ul);
    uint64_t lo = v << s;
    U32Ptr words = U32Ptr(pc.words);
    if (uint(lo) != 0u) {
        atomicOr(words.v[w], uint(lo));
    }
    if (uint(lo >> 32) != 0u) {
        atomicOr(words.v[w + 1u], uint(lo >> 32));
    }
    if (s + e > 64u && uint(v >> (64u - s)) != 0u) {
        atomicOr(words.v[w + 2u], uint(v >> (64u - s)));
    }
}
