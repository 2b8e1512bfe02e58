#version 460
// Compressed-tree build, level pc.level, one invocation per node: its preorder key (the child
// indices from the root down as the digits of a Morton code, lattice::preorder_key) into
// scratch and its index into scratch2, for the radix sort that orders the level.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.count) {
        return;
    }
    uvec3 q = ct_coords(pc.level, i);
    uint key = 0u;
    for (uint bit = pc.level; bit > 0u; --bit) {
        for (uint k = 0u; k < pc.dims; ++k) {
            key = (key << 1) | ((q[pc.dims - 1u - k] >> (bit - 1u)) & 1u);
        }
    }
    U32Ptr(pc.scratch).v[i] = key;
    U32Ptr(pc.scratch2).v[i] = i;
}
