#version 460
// Compressed-tree packing, level pc.level, one invocation per candidate scale: the feasible
// candidate with the least padding, the smallest scale among equals (as pack::search_scale),
// by a 64-bit atomicMin of (padding << 32 | scale).
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint c = uint(global_index());
    if (c >= pc.candidates) {
        return;
    }
    uint64_t total = U64Ptr(pc.scratch).v[c];
    if (total < (1ul << CTREE_INFEASIBLE_SHIFT)) {
        uint64_t best = (total << 32) | uint64_t(pc.first_scale + c);
        atomicMin(U64Ptr(pc.stats).v[ct_stat_index(pc.level, CTREE_STAT_BEST)], best);
    }
}
