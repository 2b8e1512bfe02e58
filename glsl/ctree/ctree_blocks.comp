#version 460
// Compressed-tree packing, level pc.level, one invocation per record: the block size at the
// level's chosen scale (the record, then its internal children's padded blocks), and the sum
// of the level's blocks.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint j = uint(global_index());
    if (j >= pc.records) {
        return;
    }
    uint l = pc.level;
    uint i = ct_records(l).v[j];
    uint scale = uint(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_BEST)] & 0xfffffffful);
    uint padding;
    bool fits;
    uint end = ct_place(l, i, scale, padding, fits);
    uint block = 1u + ct_child_count(ct_open(l, ct_coords(l, i))) + end;
    ct_blocks(l).v[i] = block;
    atomicAdd(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_BLOCKS)], uint64_t(block));
}
