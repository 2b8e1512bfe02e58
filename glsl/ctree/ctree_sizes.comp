#version 460
// Compressed-tree layout, the forest level pc.level, one invocation per record in preorder: its
// block size into scratch (mode 0, for the scan that places the clipped subtrees one after
// another), or its address from the scanned scratch2 (mode 1, pc.candidates = 1).
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint j = uint(global_index());
    if (j >= pc.records) {
        return;
    }
    uint l = pc.level;
    uint i = ct_records(l).v[j];
    if (pc.candidates == 0u) {
        U32Ptr(pc.scratch).v[j] = ct_blocks(l).v[i];
    } else {
        ct_addresses(l).v[i] = U32Ptr(pc.scratch2).v[j];
    }
}
