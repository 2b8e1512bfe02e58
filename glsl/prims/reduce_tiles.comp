#version 460
// Reduces each SCAN_TILE-word tile of `src` to one word of `dst` with the operator chosen by
// specialization constant 1 (REDUCE_OP_SUM wrapping, REDUCE_OP_MIN, REDUCE_OP_MAX).
// Used by reduce (repeated until one word is left) and by scan (the tile totals).
#include "common.glsl"
#include "scan_tile.glsl"

layout(constant_id = 1) const uint OP = REDUCE_OP_SUM;

layout(push_constant, scalar) uniform Push {
    uint64_t src;
    uint64_t dst;
    uint n;
} pc;

shared uint s_subgroup[gl_WorkGroupSize.x];

uint identity() {
    return OP == REDUCE_OP_MIN ? 0xffffffffu : 0u;
}

uint combine(uint a, uint b) {
    if (OP == REDUCE_OP_MIN) return min(a, b);
    if (OP == REDUCE_OP_MAX) return max(a, b);
    return a + b;
}

uint subgroup_combine(uint a) {
    if (OP == REDUCE_OP_MIN) return subgroupMin(a);
    if (OP == REDUCE_OP_MAX) return subgroupMax(a);
    return subgroupAdd(a);
}

void main() {
    uint tile = group_index();
    uint base = tile * SCAN_TILE;
    if (base >= pc.n) {
        return;
    }
    uint v[SCAN_ITEMS_PER_THREAD];
    load_items(pc.src, base + gl_LocalInvocationID.x * SCAN_ITEMS_PER_THREAD, pc.n, identity(), v);
    uint acc = v[0];
    for (uint j = 1; j < SCAN_ITEMS_PER_THREAD; ++j) {
        acc = combine(acc, v[j]);
    }
    acc = subgroup_combine(acc);
    if (subgroupElect()) {
        s_subgroup[gl_SubgroupID] = acc;
    }
    barrier();
    if (gl_LocalInvocationID.x == 0) {
        uint total = s_subgroup[0];
        for (uint s = 1; s < gl_NumSubgroups; ++s) {
            total = combine(total, s_subgroup[s]);
        }
        U32Ptr(pc.dst).v[tile] = total;
    }
}
