#version 460
// Compressed-tree packing, level pc.level, one invocation per record: the largest unpadded
// offset of an internal child's block (the blocks of all internal children before the last),
// the y_max that bounds the scale search.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint j = uint(global_index());
    if (j >= pc.records) {
        return;
    }
    uint l = pc.level;
    uint i = ct_records(l).v[j];
    uvec3 q = ct_coords(l, i);
    uvec3 open = ct_open(l, q);
    uint sum = 0u;
    uint last = 0u;
    for (uint c = 0u; c < (1u << pc.dims); ++c) {
        if (!ct_child_exists(open, c)) {
            continue;
        }
        uint b = ct_blocks(l + 1u).v[ct_index(l + 1u, ct_child(l, q, c))];
        if (b != 0u) {
            sum += b;
            last = b;
        }
    }
    atomicMax(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_MAX_OFFSET)], uint64_t(sum - last));
}
