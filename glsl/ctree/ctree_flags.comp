#version 460
// Compressed-tree build, level pc.level, one invocation per preorder rank: the internal flag of
// the node of that rank (scratch2 holds the preorder permutation), for the compaction that
// lists the level's records in preorder.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint r = uint(global_index());
    if (r >= pc.count) {
        return;
    }
    U32Ptr(pc.scratch).v[r] = ct_internal(pc.level).v[U32Ptr(pc.scratch2).v[r]];
}
