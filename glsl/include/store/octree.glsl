// Lookups in the N^3-tree texture store (compute/src/store/octree.rs; Lefebvre, Hornus and
// Neyret 2005). The node pool is one array of RGBA8 words. A node of level l starts at word
// 8 * address: word 0 holds the node's average colour (MIP), words 1 + x + N(y + N z) its N^3
// cells, N = n[l]. A cell's alpha byte is its tag: 0 empty, 1 child pointer (the low 24 bits
// are the child's address), 2..255 a leaf colour stored in place (autumnal tree). The root is
// at address 0; level l's cells span span[l] voxels per axis (span[levels - 1] = 1).
//
// Use from any kernel:
//     #include "common.glsl"
//     #include "store/octree.glsl"
//     vec4 c = store_octree_nearest(p, pos);        // pos in [0,1]^3 object space: 1 descent
//     vec4 t = store_octree_trilinear(p, pos);      // 8 descents over the interpolation voxels
//     vec4 m = store_octree_mip(p, pos, depth);     // average colour of the node at `depth`
// The struct is 104 bytes in scalar layout and must be filled with the bytes of the Rust
// `OctreeParams` (same field order):
//     struct OctreeParams {
//         uint64_t pool;        // device address of the node pool (uint words)
//         uint resolution;      // R = n[0] * n[1] * ... * n[levels - 1]
//         uint levels;          // 1..=OCTREE_MAX_LEVELS
//         uint n[11];           // N of each level
//         uint span[11];        // voxels per cell of each level
//     };
// A voxel that is not stored reads as vec4(0) (alpha 0).
#ifndef LAZYSOLID_STORE_OCTREE_GLSL
#define LAZYSOLID_STORE_OCTREE_GLSL

#include "store/texels.glsl"

#define OCTREE_MAX_LEVELS 11

struct OctreeParams {
    uint64_t pool;
    uint resolution;
    uint levels;
    uint n[OCTREE_MAX_LEVELS];
    uint span[OCTREE_MAX_LEVELS];
};

// Index of the word of `voxel`'s cell in the node at `address` of level l.
uint store_octree_cell(OctreeParams p, uint address, uint l, uvec3 voxel) {
    uint n = p.n[l];
    uvec3 c = (voxel / p.span[l]) % n;
    return 8u * address + 1u + c.x + n * (c.y + n * c.z);
}

// RGBA8 of a voxel (a leaf may sit above the finest level), or 0 when it is not stored.
uint store_octree_texel(OctreeParams p, uvec3 voxel) {
    U32Ptr pool = U32Ptr(p.pool);
    uint address = 0u;
    for (uint l = 0u; l < p.levels; ++l) {
        uint e = pool.v[store_octree_cell(p, address, l, voxel)];
        uint tag = e >> 24;
        if (tag == 0u) {
            return 0u;
        }
        if (tag >= 2u) {
            return e;
        }
        address = e & 0xffffffu;
    }
    return 0u;
}

vec4 store_octree_nearest(OctreeParams p, vec3 pos) {
    return store_unpack(store_octree_texel(p, store_nearest_voxel(pos, p.resolution)));
}

StoreSample store_octree_sample(OctreeParams p, vec3 pos) {
    ivec3 base;
    vec3 f;
    store_trilinear_footprint(pos, p.resolution, base, f);
    StoreSample s = store_sample_empty();
    for (int o = 0; o < 8; ++o) {
        store_sample_add(s, store_octree_texel(p, store_corner(base, o, p.resolution)), store_corner_weight(f, o),
                         store_corner_weight_gradient(f, o, p.resolution));
    }
    return s;
}

vec4 store_octree_trilinear(OctreeParams p, vec3 pos) {
    return store_octree_sample(p, pos).sum;
}

// The average colour of the node of level `depth` containing pos (depth 0: the root's); a
// leaf met on the way is returned itself, an empty cell as vec4(0). depth >= levels gives the
// nearest texel.
vec4 store_octree_mip(OctreeParams p, vec3 pos, uint depth) {
    U32Ptr pool = U32Ptr(p.pool);
    uvec3 voxel = store_nearest_voxel(pos, p.resolution);
    uint address = 0u;
    for (uint l = 0u; l < p.levels; ++l) {
        if (l == depth) {
            return store_unpack(pool.v[8u * address]);
        }
        uint e = pool.v[store_octree_cell(p, address, l, voxel)];
        uint tag = e >> 24;
        if (tag == 0u) {
            return vec4(0.0);
        }
        if (tag >= 2u) {
            return store_unpack(e);
        }
        address = e & 0xffffffu;
    }
    return vec4(0.0);
}

#endif
