// Shared by the TileTree fill kernels (compute/src/store/tiletree/gpu.rs): one push block, the
// tile owning a texel (binary search over the tiles' first texels), and the column-triangle
// intersection of compute/src/store/tiletree/geometry.rs, operation for operation.
#ifndef LAZYSOLID_STORE_TILETREE_BUILD_GLSL
#define LAZYSOLID_STORE_TILETREE_BUILD_GLSL

#include "common.glsl"
#include "morton.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t tiles;       // TILETREE_TILE_WORDS (12) uint per tile, packing order
    uint64_t triangles;   // candidate triangle indices of all tiles
    uint64_t positions;   // vertex positions in grid units (3 floats each)
    uint64_t indices;     // triangles' vertex indices (3 uints each)
    uint64_t keys;        // per texel: Morton key of the voxel its colour comes from
    uint64_t colours;     // per texel: RGBA8
    uint64_t filled_in;   // per texel: 1 when its colour is defined (read)
    uint64_t filled_out;  // per texel: 1 when its colour is defined (written)
    uint64_t map;         // the tile map
    uint n_tiles;
    uint n_texels;
    uint resolution;
    uint map_width;
    uint mode;            // dilation: 0 rows, 1 columns
} pc;

const float TILETREE_MARGIN = 3.0;

struct TileRecord {
    uvec3 origin;
    uint side;     // T: the leaf's side (its slab along the face axis)
    uint face;
    uint tri_start;
    uint tri_count;
    uint texel_offset;
    uvec2 corner;
    uvec2 rect_origin;  // first column along (b, c), relative to the leaf's origin
    uvec2 size;         // stored texels per row and column: w + 2, h + 2
};

// The tile owning texel t: the last tile whose texel offset is <= t.
uint tiletree_tile_of(uint t) {
    U32Ptr tiles = U32Ptr(pc.tiles);
    uint lo = 0u;
    uint hi = pc.n_tiles;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (tiles.v[TILETREE_TILE_WORDS * mid + 7u] <= t) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

TileRecord tiletree_tile(uint k) {
    U32Ptr tiles = U32Ptr(pc.tiles);
    uint o = TILETREE_TILE_WORDS * k;
    TileRecord r;
    r.origin = uvec3(tiles.v[o], tiles.v[o + 1u], tiles.v[o + 2u]);
    r.side = tiles.v[o + 3u];
    r.face = tiles.v[o + 4u];
    r.tri_start = tiles.v[o + 5u];
    r.tri_count = tiles.v[o + 6u];
    r.texel_offset = tiles.v[o + 7u];
    r.corner = uvec2(tiles.v[o + 8u], tiles.v[o + 9u]);
    uint x0y0 = tiles.v[o + 10u];
    uint wh = tiles.v[o + 11u];
    r.rect_origin = uvec2(x0y0 & 0xffffu, x0y0 >> 16);
    r.size = uvec2((wh & 0xffffu) + 2u, (wh >> 16) + 2u);
    return r;
}

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer TileTreeVec3 { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer TileTreeUvec3 { uvec3 v[]; };

// Where the column along axis a through (cu, cv) meets triangle tri; false when it misses or
// the triangle is edge-on. Edges count as hits.
bool tiletree_column_hit(uint tri, uint a, float cu, float cv, out float h) {
    uvec3 idx = TileTreeUvec3(pc.indices).v[tri];
    TileTreeVec3 pos = TileTreeVec3(pc.positions);
    vec3 v0 = pos.v[idx.x];
    vec3 v1 = pos.v[idx.y];
    vec3 v2 = pos.v[idx.z];
    uint b = (a + 1u) % 3u;
    uint c = (a + 2u) % 3u;
    precise float e0 = (v2[b] - v1[b]) * (cv - v1[c]) - (v2[c] - v1[c]) * (cu - v1[b]);
    precise float e1 = (v0[b] - v2[b]) * (cv - v2[c]) - (v0[c] - v2[c]) * (cu - v2[b]);
    precise float e2 = (v1[b] - v0[b]) * (cv - v0[c]) - (v1[c] - v0[c]) * (cu - v0[b]);
    precise float area = e0 + e1 + e2;
    if (area == 0.0) {
        return false;
    }
    bool inside = (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0);
    if (!inside) {
        return false;
    }
    precise float num = e0 * v0[a] + e1 * v1[a] + e2 * v2[a];
    h = num / area;
    return true;
}

#endif
