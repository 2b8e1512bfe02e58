// Lookups in the coherent-hash store (compute/src/store/hash_store.rs): a Robin Hood table
// with the coherent probe sequence, keyed by the voxel's 3D Morton key, whose payload is the
// index of the texel's RGBA8 colour.
//
// Use from any kernel:
//     #include "common.glsl"            // buffer_reference types, int64
//     #include "store/hash.glsl"        // defines CELL_BITS 64 unless already 64
//     ... HashStoreParams p = <from your own push constant / buffer>;
//     vec4 c = store_hash_nearest(p, pos);      // pos in [0,1]^3 object space
//     vec4 t = store_hash_trilinear(p, pos);    // 8 hash queries
// The struct is 40 bytes in scalar layout and must be filled with the bytes of the Rust
// `HashStoreParams` (same field order):
//     struct HashStoreParams {
//         uint64_t cells;       // device address of the table's 64-bit cells
//         uint64_t colours;     // device address of the RGBA8 colours (uint per texel)
//         uint64_t fastmod_m;   // table-size reciprocal for the modulo
//         uint table_size;      // cells
//         uint key_bits;        // bits of key + 1 in a cell
//         uint probe;           // HASH_PROBE_COHERENT or HASH_PROBE_RANDOM
//         uint resolution;      // R
//     };
// A voxel that is not stored reads as vec4(0) (alpha 0).
// Requires GL_EXT_shader_atomic_int64 (enabled by the hash cell include).
#ifndef LAZYSOLID_STORE_HASH_GLSL
#define LAZYSOLID_STORE_HASH_GLSL

#ifndef CELL_BITS
#define CELL_BITS 64
#endif
#if CELL_BITS != 64
#error store/hash.glsl needs the 64-bit Robin Hood cells (CELL_BITS 64)
#endif

#include "morton.glsl"
#include "hash/robin_hood_lookup.glsl"
#include "store/texels.glsl"

struct HashStoreParams {
    uint64_t cells;
    uint64_t colours;
    uint64_t fastmod_m;
    uint table_size;
    uint key_bits;
    uint probe;
    uint resolution;
};

// RGBA8 of a voxel, or 0 when it is not stored.
uint store_hash_texel(HashStoreParams p, uvec3 voxel) {
    uint index = robin_hood_lookup(p.cells, p.table_size, p.fastmod_m, p.key_bits, p.probe, morton3(voxel));
    return index == HASH_NOT_FOUND ? 0u : U32Ptr(p.colours).v[index];
}

vec4 store_hash_nearest(HashStoreParams p, vec3 pos) {
    return store_unpack(store_hash_texel(p, store_nearest_voxel(pos, p.resolution)));
}

StoreSample store_hash_sample(HashStoreParams p, vec3 pos) {
    ivec3 base;
    vec3 f;
    store_trilinear_footprint(pos, p.resolution, base, f);
    StoreSample s = store_sample_empty();
    for (int o = 0; o < 8; ++o) {
        store_sample_add(s, store_hash_texel(p, store_corner(base, o, p.resolution)), store_corner_weight(f, o),
                         store_corner_weight_gradient(f, o, p.resolution));
    }
    return s;
}

vec4 store_hash_trilinear(HashStoreParams p, vec3 pos) {
    return store_hash_sample(p, pos).sum;
}

#endif
