#version 460
// Octree build, cells of the parent level (N = span; the parent is found among search_keys,
// or is the root):
// mode 0: new node src[i] at address aux[i]: its parent cell becomes a child pointer;
// mode 1: voxel src[i]: counter[0] += 1 when its leaf cell is not empty (already stored);
// mode 2: voxel src[i]: its leaf cell becomes colour aux[i];
// mode 3: voxel src[i]: counter[1] += 1 when it is not stored (no leaf colour);
// mode 4: voxel src[i]: its stored leaf colour becomes aux[i] (after mode 3 found none absent).
#include "store/octree_build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uvec3 c = morton3_decode(U64Ptr(pc.src).v[i]);
    uint n = pc.span;
    uint parent = octree_parent_address(morton3(c / n));
    uvec3 cell = c % n;
    uint word = 8u * parent + 1u + cell.x + n * (cell.y + n * cell.z);
    U32Ptr pool = U32Ptr(pc.pool);
    U32Ptr counter = U32Ptr(pc.counter);
    if (pc.mode == 0u) {
        pool.v[word] = (1u << 24) | U32Ptr(pc.aux).v[i];
    } else if (pc.mode == 1u) {
        if (parent != OCTREE_NONE && pool.v[word] != 0u) {
            atomicAdd(counter.v[0], 1u);
        }
    } else if (pc.mode == 2u) {
        pool.v[word] = U32Ptr(pc.aux).v[i];
    } else if (pc.mode == 3u) {
        if (parent == OCTREE_NONE || (pool.v[word] >> 24) < 2u) {
            atomicAdd(counter.v[1], 1u);
        }
    } else {
        pool.v[word] = U32Ptr(pc.aux).v[i];
    }
}
