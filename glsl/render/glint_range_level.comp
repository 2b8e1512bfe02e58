#version 460
// One level of the glint range table (renderer/src/glint/range_table.rs, its CPU twin): entry
// (x, y) is the union of the 4 entries of the level below at offsets 0 and `offset`, or empty
// when the level's square [x, x + span]^2 leaves the example. Entries pack four 16-bit values:
// (min n_x | min n_y << 16, max n_x | max n_y << 16).
#include "common.glsl"
#include "glint/range_union.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Entries { uvec2 v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t src;
    uint64_t dst;
    uint size;
    uint offset;
    uint span;
} pc;

void main() {
    uint64_t i = global_index();
    uint n = pc.size;
    if (i >= uint64_t(n) * uint64_t(n)) {
        return;
    }
    uint x = uint(i % uint64_t(n));
    uint y = uint(i / uint64_t(n));
    Entries dst = Entries(pc.dst);
    if (x + pc.span > n - 1u || y + pc.span > n - 1u) {
        dst.v[uint(i)] = GLINT_RANGE_EMPTY;
        return;
    }
    Entries src = Entries(pc.src);
    uint at = y * n + x;
    uint up = pc.offset * n;
    uvec2 a = range_union(src.v[at], src.v[at + pc.offset]);
    uvec2 b = range_union(src.v[at + up], src.v[at + up + pc.offset]);
    dst.v[uint(i)] = range_union(a, b);
}
