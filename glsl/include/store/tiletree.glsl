// Lookups in the TileTree store (compute/src/store/tiletree/; Lefebvre and Dachsbacher 2007):
// an octree around the surface whose leaves carry 2D tiles on up to six faces, packed into one
// tile map. A lookup descends to the leaf holding the point, picks the face from the surface
// normal, projects the point in parallel onto it and reads the tile: 1 descent + 4 texels.
//
// Layout (all uint words):
//   nodes:  8 cells per node (octant x | y << 1 | z << 2); a cell is 0 (empty), node index + 1,
//           or TILETREE_LEAF | leaf index. The root's entry is `root`.
//   leaves: TILETREE_LEAF_WORDS (14) words per leaf: origin x | y << 16; origin z | depth << 16
//           | face mask << 24; then per face f (2 * axis + (sign < 0)) two words: its tile's map
//           corner x | y << 16, and its rectangle of columns x0 | y0 << 8 | (w - 1) << 16 |
//           (h - 1) << 24 (relative to the leaf's origin).
//   map:    the tile map, RGBA8 words, row-major, `map_width` wide. A tile holds its w x h
//           columns plus a one-texel border: (w + 2) x (h + 2) texels, texel (x, y) at the
//           leaf's column (origin_b + x0 + x - 1, origin_c + y0 + y - 1), b, c the face's
//           in-plane axes (axis + 1, axis + 2 mod 3).
//
// Use from any kernel:
//     #include "common.glsl"
//     #include "store/tiletree.glsl"
//     vec4 c = store_tiletree_bilinear(p, pos, normal);  // pos in [0,1]^3, normal need not be unit
//     vec4 n = store_tiletree_nearest(p, pos, normal);
// The struct is 40 bytes in scalar layout and must be filled with the bytes of the Rust
// `TileTreeParams` (same field order):
//     struct TileTreeParams {
//         uint64_t nodes;       // device address of the node cells
//         uint64_t leaves;      // device address of the leaf records
//         uint64_t map;         // device address of the tile map
//         uint root;            // the root's entry
//         uint resolution;      // R, a power of two
//         uint map_width;       // tile map width in texels
//         uint pad;             // 0
//     };
// A point in empty space reads as vec4(0) (alpha 0). Must match
// compute/src/store/tiletree/lookup_cpu.rs.
#ifndef LAZYSOLID_STORE_TILETREE_GLSL
#define LAZYSOLID_STORE_TILETREE_GLSL

#include "store/texels.glsl"

#define TILETREE_LEAF 0x80000000u

struct TileTreeParams {
    uint64_t nodes;
    uint64_t leaves;
    uint64_t map;
    uint root;
    uint resolution;
    uint map_width;
    uint pad;
};

// The leaf holding `voxel`, or 0xffffffff in empty space.
uint store_tiletree_leaf(TileTreeParams p, uvec3 voxel) {
    U32Ptr nodes = U32Ptr(p.nodes);
    uint levels = findLSB(p.resolution);
    uint e = p.root;
    for (uint d = 0u; d < levels && e != 0u && (e & TILETREE_LEAF) == 0u; ++d) {
        uint shift = levels - 1u - d;
        uvec3 bit = (voxel >> shift) & 1u;
        e = nodes.v[8u * (e - 1u) + bit.x + (bit.y << 1) + (bit.z << 2)];
    }
    return (e & TILETREE_LEAF) != 0u ? (e & ~TILETREE_LEAF) : 0xffffffffu;
}

// The dominant face of n (ties to the lower axis), or the tiled face facing n most.
uint store_tiletree_face(uint mask, vec3 n) {
    vec3 an = abs(n);
    uint a = 0u;
    if (an.y > an[a]) {
        a = 1u;
    }
    if (an.z > an[a]) {
        a = 2u;
    }
    uint f = 2u * a + (n[a] < 0.0 ? 1u : 0u);
    if ((mask & (1u << f)) != 0u) {
        return f;
    }
    float best = -1.0 / 0.0;
    uint pick = f;
    for (uint g = 0u; g < 6u; ++g) {
        if ((mask & (1u << g)) != 0u) {
            float score = (g & 1u) == 0u ? n[g / 2u] : -n[g / 2u];
            if (score > best) {
                best = score;
                pick = g;
            }
        }
    }
    return pick;
}

// Shared by both filters: the tile of the leaf and face at pos (its map corner and its
// rectangle's width and height in columns) and the in-tile coordinate; false in empty space.
bool store_tiletree_tile(TileTreeParams p, vec3 pos, vec3 n, out uvec2 corner, out uvec2 size, out vec2 t,
                         out uint face) {
    precise vec3 g = pos * float(p.resolution);
    uvec3 voxel = uvec3(clamp(floor(g), vec3(0.0), vec3(float(p.resolution) - 1.0)));
    uint leaf = store_tiletree_leaf(p, voxel);
    if (leaf == 0xffffffffu) {
        return false;
    }
    U32Ptr leaves = U32Ptr(p.leaves);
    uint base = TILETREE_LEAF_WORDS * leaf;
    uint w0 = leaves.v[base];
    uint w1 = leaves.v[base + 1u];
    uvec3 origin = uvec3(w0 & 0xffffu, w0 >> 16, w1 & 0xffffu);
    face = store_tiletree_face(w1 >> 24, n);
    uint c = leaves.v[base + 2u + 2u * face];
    uint r = leaves.v[base + 3u + 2u * face];
    corner = uvec2(c & 0xffffu, c >> 16);
    size = uvec2(((r >> 16) & 0xffu) + 1u, (r >> 24) + 1u);
    uint a = face / 2u;
    uint b = (a + 1u) % 3u;
    uint cc = (a + 2u) % 3u;
    precise float tb = (g[b] - float(origin[b] + (r & 0xffu))) + 0.5;
    precise float tc = (g[cc] - float(origin[cc] + ((r >> 8) & 0xffu))) + 0.5;
    t = vec2(tb, tc);
    return true;
}

vec4 store_tiletree_nearest(TileTreeParams p, vec3 pos, vec3 n) {
    uvec2 corner;
    uvec2 size;
    vec2 t;
    uint face;
    if (!store_tiletree_tile(p, pos, n, corner, size, t, face)) {
        return vec4(0.0);
    }
    uvec2 xy = uvec2(clamp(floor(t + 0.5), vec2(1.0), vec2(size)));
    return unpackUnorm4x8(U32Ptr(p.map).v[(corner.y + xy.y) * p.map_width + corner.x + xy.x]);
}

// The bilinear lookup with its coverage (1 on a tile, whose texels are all written; 0 in
// empty space) and the gradient of alpha: in the face's plane (axes b, c), 0 along its normal.
StoreSample store_tiletree_sample(TileTreeParams p, vec3 pos, vec3 n) {
    uvec2 corner;
    uvec2 size;
    vec2 t;
    uint face;
    StoreSample s = store_sample_empty();
    if (!store_tiletree_tile(p, pos, n, corner, size, t, face)) {
        return s;
    }
    vec2 i = clamp(floor(t), vec2(0.0), vec2(size));
    precise vec2 f = clamp(t - i, vec2(0.0), vec2(1.0));
    uvec2 xy = uvec2(i);
    U32Ptr map = U32Ptr(p.map);
    uint base = (corner.y + xy.y) * p.map_width + corner.x + xy.x;
    vec4 c00 = unpackUnorm4x8(map.v[base]);
    vec4 c10 = unpackUnorm4x8(map.v[base + 1u]);
    vec4 c01 = unpackUnorm4x8(map.v[base + p.map_width]);
    vec4 c11 = unpackUnorm4x8(map.v[base + p.map_width + 1u]);
    precise vec4 r = (c00 * (1.0 - f.x) + c10 * f.x) * (1.0 - f.y) + (c01 * (1.0 - f.x) + c11 * f.x) * f.y;
    s.sum = r;
    s.coverage = 1.0;
    float res = float(p.resolution);
    float d_b = ((c10.a - c00.a) * (1.0 - f.y) + (c11.a - c01.a) * f.y) * res;
    float d_c = ((c01.a - c00.a) * (1.0 - f.x) + (c11.a - c10.a) * f.x) * res;
    uint a = face / 2u;
    s.gradient[(a + 1u) % 3u] = d_b;
    s.gradient[(a + 2u) % 3u] = d_c;
    return s;
}

vec4 store_tiletree_bilinear(TileTreeParams p, vec3 pos, vec3 n) {
    return store_tiletree_sample(p, pos, n).sum;
}

#endif
