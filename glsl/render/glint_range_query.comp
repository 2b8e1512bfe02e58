#version 460
// A batch of range queries over the glint example (renderer/src/glint/minmax_mip.rs and
// range_table.rs are the CPU twins): the packed interval of n over the example square
// [x, x + 2^level]^2, i.e. over its (2^level + 1)^2 quantized texels, by one of three methods
// with identical answers:
// 0: the sparse table, one lookup of level `level` at (x, y);
// 1: the min-max mip, the union of the square's maximal aligned blocks (the product of both
//    axes' dyadic decompositions, each 2^i x 2^j rectangle cut into 2^|i-j| squares);
// 2: brute force, every quantized texel of the square.
#include "common.glsl"
#include "glint/range_union.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Entries { uvec2 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Squares { uvec3 v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t structure;
    uint64_t squares;
    uint64_t results;
    uint count;
    uint size;
    uint method;
} pc;

// Largest aligned interval that starts at p and ends at most at `end` (exclusive): its log2.
uint dyadic_step(uint p, uint end) {
    uint align = p == 0u ? 31u : uint(findLSB(p));
    return min(align, uint(findMSB(end - p)));
}

uvec2 mip_query(Entries mip, uint n, uint x, uint y, uint span) {
    // Both axes' pieces are recomputed as the loops go (no per-invocation arrays, which
    // lavapipe keeps in scratch memory).
    uvec2 acc = GLINT_RANGE_EMPTY;
    uint xend = x + span;
    uint yend = y + span;
    for (uint py = y; py < yend;) {
        uint j = dyadic_step(py, yend);
        for (uint px = x; px < xend;) {
            uint i = dyadic_step(px, xend);
            uint m = min(i, j);
            uint e = n >> m;
            uint at = 4u * (n * n - e * e) / 3u + (py >> m) * e + (px >> m);
            uint blocks = 1u << (max(i, j) - m);
            uint stride = i > j ? 1u : e;
            for (uint t = 0u; t < blocks; t++) {
                acc = range_union(acc, mip.v[at + t * stride]);
            }
            px += 1u << i;
        }
        py += 1u << j;
    }
    return acc;
}

uvec2 brute_force(Entries texels, uint n, uint x, uint y, uint span) {
    uvec2 acc = GLINT_RANGE_EMPTY;
    for (uint yy = y; yy < y + span; yy++) {
        for (uint xx = x; xx < x + span; xx++) {
            acc = range_union(acc, texels.v[yy * n + xx]);
        }
    }
    return acc;
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.count) {
        return;
    }
    uvec3 q = Squares(pc.squares).v[i];
    uint n = pc.size;
    Entries s = Entries(pc.structure);
    // (2^level + 1) texels per side.
    uint span = (1u << q.z) + 1u;
    uvec2 r;
    if (pc.method == 0u) {
        r = s.v[(q.z * n + q.y) * n + q.x];
    } else if (pc.method == 1u) {
        r = mip_query(s, n, q.x, q.y, span);
    } else {
        r = brute_force(s, n, q.x, q.y, span);
    }
    Entries(pc.results).v[i] = r;
}
