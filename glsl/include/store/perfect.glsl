// Lookups in the perfect-hash store (compute/src/store/perfect_store.rs): a perfect spatial
// hash (hash/perfect.glsl) of the voxels' grid points whose payload is the texel's RGBA8
// colour itself (texel layout), or of blocks of interpolation cells whose payload is a block
// of (b+1)³ texels with duplicated borders (blocked layout, hash/perfect_blocked.glsl).
//
// Use from any kernel:
//     #include "common.glsl"
//     #include "store/perfect.glsl"
//     ... PerfectStoreParams p = <from your own push constant / buffer>;
//     vec4 c = store_perfect_nearest(p, pos);    // pos in [0,1]^3 object space
//     vec4 t = store_perfect_trilinear(p, pos);  // texel layout: 8 lookups (two reads each);
//                                                // blocked layout: one offset read, one block
// The struct is 72 bytes in scalar layout, the bytes of the Rust `PerfectStoreParams`:
//     struct PerfectStoreParams {
//         PerfectHashParams table;  // 56 bytes, see hash/perfect.glsl
//         uint resolution;          // R
//         uint block;               // b of the blocked layout, 0 for the texel layout
//         uint unconstrained;       // 1: absent voxels read vec4(0) (tags checked)
//         uint pad;
//     };
// With constrained access (no keys stored: the thesis' texturing case) only stored voxels may
// be read; any other voxel reads some stored texel.
#ifndef LAZYSOLID_STORE_PERFECT_GLSL
#define LAZYSOLID_STORE_PERFECT_GLSL

#include "hash/perfect.glsl"
#include "hash/perfect_blocked.glsl"
#include "store/texels.glsl"

struct PerfectStoreParams {
    PerfectHashParams table;
    uint resolution;
    uint block;
    uint unconstrained;
    uint pad;
};

// RGBA8 of a voxel of the texel layout (0 when absent and the access is unconstrained).
uint store_perfect_texel(PerfectStoreParams p, uvec3 voxel) {
    if (p.unconstrained != 0u) {
        uint v;
        return perfect_find(p.table, voxel, v) ? v : 0u;
    }
    return perfect_lookup(p.table, voxel);
}

// The texel of the voxel containing pos, read from the block that holds its trilinear
// footprint (blocked layout): the footprint corner nearest to pos is that voxel.
uint store_perfect_block_nearest(PerfectStoreParams p, vec3 pos) {
    precise vec3 q = pos * float(p.resolution) - 0.5;
    vec3 fl = floor(q);
    uvec3 j = uvec3(clamp(ivec3(fl) + 1, ivec3(0), ivec3(int(p.resolution))));
    uvec3 d = uvec3(greaterThanEqual(q - fl, vec3(0.5)));
    uvec3 b = j / p.block;
    uvec3 t = j - b * p.block + d;
    uint side = p.block + 1u;
    uint s = perfect_slot(p.table, b);
    return U32Ptr(p.table.data).v[s * p.table.block_words + t.x + side * (t.y + side * t.z)];
}

vec4 store_perfect_nearest(PerfectStoreParams p, vec3 pos) {
    if (p.block != 0u) {
        return store_unpack(store_perfect_block_nearest(p, pos));
    }
    return store_unpack(store_perfect_texel(p, store_nearest_voxel(pos, p.resolution)));
}

// The blocked layout's sample: the same 8 texels as its trilinear lookup, read from one block.
StoreSample store_perfect_blocked_sample(PerfectStoreParams p, vec3 pos) {
    uint base;
    uvec3 local;
    vec3 f;
    perfect_blocked_footprint(p.table, p.block, p.resolution, pos, base, local, f);
    StoreSample s = store_sample_empty();
    for (int o = 0; o < 8; ++o) {
        store_sample_add(s, perfect_blocked_texel(p.table, p.block, base, local, o), store_corner_weight(f, o),
                         store_corner_weight_gradient(f, o, p.resolution));
    }
    return s;
}

StoreSample store_perfect_sample(PerfectStoreParams p, vec3 pos) {
    if (p.block != 0u) {
        return store_perfect_blocked_sample(p, pos);
    }
    ivec3 base;
    vec3 f;
    store_trilinear_footprint(pos, p.resolution, base, f);
    StoreSample s = store_sample_empty();
    for (int o = 0; o < 8; ++o) {
        store_sample_add(s, store_perfect_texel(p, store_corner(base, o, p.resolution)), store_corner_weight(f, o),
                         store_corner_weight_gradient(f, o, p.resolution));
    }
    return s;
}

vec4 store_perfect_trilinear(PerfectStoreParams p, vec3 pos) {
    if (p.block != 0u) {
        return perfect_blocked_trilinear(p.table, p.block, p.resolution, pos);
    }
    return store_perfect_sample(p, pos).sum;
}

#endif
