// Shared by the octree build kernels (compute/src/store/octree.rs): one push block, and the
// binary search of a node key among a level's sorted keys.
#ifndef LAZYSOLID_STORE_OCTREE_BUILD_GLSL
#define LAZYSOLID_STORE_OCTREE_BUILD_GLSL

#extension GL_EXT_shader_atomic_int64 : require
#include "common.glsl"
#include "morton.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t src;          // u64 keys processed, one per invocation
    uint64_t dst;          // u64 keys written
    uint64_t aux;          // u32 per key: flags, scanned offsets, addresses or colours
    uint64_t dst_addrs;    // u32 addresses written with dst
    uint64_t search_keys;  // sorted u64 node keys of the level searched
    uint64_t search_addrs; // their addresses
    uint64_t pool;         // the node pool
    uint64_t counter;      // u32 failure counters
    uint n;
    uint search_count;
    uint span;             // voxels per node (node keys), or N of the parent level (links)
    uint mode;
    uint base;             // first free address (new nodes)
    uint stride;           // addresses per node (new nodes)
    uint root_parent;      // 1 when the parent level is the root, at address 0
} pc;

const uint OCTREE_NONE = 0xffffffffu;

// Index of `key` in search_keys, or OCTREE_NONE.
uint octree_search(uint64_t key) {
    U64Ptr keys = U64Ptr(pc.search_keys);
    uint lo = 0u;
    uint hi = pc.search_count;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        uint64_t k = keys.v[mid];
        if (k == key) {
            return mid;
        }
        if (k < key) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return OCTREE_NONE;
}

// Address of the parent node with key `key`, or OCTREE_NONE.
uint octree_parent_address(uint64_t key) {
    if (pc.root_parent != 0u) {
        return 0u;
    }
    uint i = octree_search(key);
    return i == OCTREE_NONE ? OCTREE_NONE : U32Ptr(pc.search_addrs).v[i];
}

#endif
