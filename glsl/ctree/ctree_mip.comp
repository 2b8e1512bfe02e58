#version 460
// Compressed-tree layout, one invocation per word of the forest's pyramid: the reconstructed
// values of levels 1..F one level after another, two i16 per word.
#include "common.glsl"
#include "ctree/build.glsl"

int ct_pyramid_value(uint e) {
    uint start = 0u;
    for (uint l = 1u; l <= pc.forest; ++l) {
        uint count = ct_count(l);
        if (e < start + count) {
            return ct_values(l).v[e - start];
        }
        start += count;
    }
    return 0;
}

void main() {
    uint w = uint(global_index());
    if (w >= pc.count) {
        return;
    }
    uint total = pc.records;
    uint lo = uint(ct_pyramid_value(2u * w)) & 0xffffu;
    uint hi = 2u * w + 1u < total ? uint(ct_pyramid_value(2u * w + 1u)) & 0xffffu : 0u;
    U32Ptr(pc.bytes).v[w] = lo | (hi << 16);
}
