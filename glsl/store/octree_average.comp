#version 460
// MIP averages of one level, children first: word 0 of node addrs[i] (or of the root) becomes
// the rounded mean, channel by channel, of its non-empty cells (a leaf's colour, a child's
// average).
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t pool;
    uint64_t addrs;
    uint n;
    uint cells_per_axis;
    uint root;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U32Ptr pool = U32Ptr(pc.pool);
    uint address = pc.root != 0u ? 0u : U32Ptr(pc.addrs).v[i];
    uint cells = pc.cells_per_axis * pc.cells_per_axis * pc.cells_per_axis;
    uvec4 sum = uvec4(0u);
    uint count = 0u;
    for (uint k = 0u; k < cells; ++k) {
        uint e = pool.v[8u * address + 1u + k];
        uint tag = e >> 24;
        if (tag == 0u) {
            continue;
        }
        uint c = tag == 1u ? pool.v[8u * (e & 0xffffffu)] : e;
        sum += uvec4(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u, c >> 24);
        count += 1u;
    }
    uint avg = 0u;
    if (count > 0u) {
        uvec4 m = (sum + count / 2u) / count;
        avg = m.x | (m.y << 8) | (m.z << 16) | (m.w << 24);
    }
    pool.v[8u * address] = avg;
}
