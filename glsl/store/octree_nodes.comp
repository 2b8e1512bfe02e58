#version 460
// Octree build, node sets of one level:
// mode 0: dst[i] = the key of the node of `span` voxels containing voxel src[i];
// mode 1: aux[i] = 1 when node key src[i] is not among the level's keys yet, else 0;
// mode 2: aux holds the scanned flags: each missing key goes to dst[aux[i]], with the new
//         address base + aux[i] * stride in dst_addrs[aux[i]].
#include "store/octree_build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t key = U64Ptr(pc.src).v[i];
    if (pc.mode == 0u) {
        U64Ptr(pc.dst).v[i] = morton3(morton3_decode(key) / pc.span);
    } else if (pc.mode == 1u) {
        U32Ptr(pc.aux).v[i] = octree_search(key) == OCTREE_NONE ? 1u : 0u;
    } else if (octree_search(key) == OCTREE_NONE) {
        uint slot = U32Ptr(pc.aux).v[i];
        U64Ptr(pc.dst).v[slot] = key;
        U32Ptr(pc.dst_addrs).v[slot] = pc.base + slot * pc.stride;
    }
}
