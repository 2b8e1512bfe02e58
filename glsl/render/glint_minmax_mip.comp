#version 460
// One level of the glint min-max mip (renderer/src/glint/minmax_mip.rs, its CPU twin): entry
// (x, y) of a level of edge `edge` is the union of the 2x2 entries (2x + i, 2y + j) of the
// level below (edge 2 * edge). Level 0 is the quantized texels.
#include "common.glsl"
#include "glint/range_union.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Entries { uvec2 v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t src;
    uint64_t dst;
    uint edge;
} pc;

void main() {
    uint i = uint(global_index());
    uint e = pc.edge;
    if (i >= e * e) {
        return;
    }
    uint x = i % e;
    uint y = i / e;
    Entries src = Entries(pc.src);
    uint at = 2u * y * (2u * e) + 2u * x;
    uvec2 a = range_union(src.v[at], src.v[at + 1u]);
    uvec2 b = range_union(src.v[at + 2u * e], src.v[at + 2u * e + 1u]);
    Entries(pc.dst).v[i] = range_union(a, b);
}
