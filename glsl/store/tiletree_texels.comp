#version 460
// TileTree fill, step 1: per texel of every tile (border included), the voxel of the surface
// point its column meets (keys[t], Morton) and whether it met one (filled_out[t]). The hit
// inside the leaf's slab nearest the face wins, else the hit nearest the slab within
// TILETREE_MARGIN voxels; without a hit, the voxel at the middle of the slab, not filled.
// Reference: texel_voxel in compute/src/store/tiletree/fill_cpu.rs.
#include "store/tiletree_build.glsl"

void main() {
    uint t = uint(global_index());
    if (t >= pc.n_texels) {
        return;
    }
    TileRecord tile = tiletree_tile(tiletree_tile_of(t));
    uint local = t - tile.texel_offset;
    uint x = local % tile.size.x;
    uint y = local / tile.size.x;
    uint a = tile.face / 2u;
    float s = (tile.face & 1u) == 0u ? 1.0 : -1.0;
    uint b = (a + 1u) % 3u;
    uint c = (a + 2u) % 3u;
    int u = int(tile.origin[b] + tile.rect_origin.x) + int(x) - 1;
    int v = int(tile.origin[c] + tile.rect_origin.y) + int(y) - 1;
    precise float cu = float(u) + 0.5;
    precise float cv = float(v) + 0.5;
    float lo = float(tile.origin[a]);
    float hi = float(tile.origin[a] + tile.side);
    bool found = false;
    uint best_class = 2u;
    float best_dist = 0.0;
    float best_sh = 0.0;
    float best_h = 0.0;
    U32Ptr tris = U32Ptr(pc.triangles);
    for (uint i = 0u; i < tile.tri_count; ++i) {
        float h;
        if (!tiletree_column_hit(tris.v[tile.tri_start + i], a, cu, cv, h)) {
            continue;
        }
        if (h < lo - TILETREE_MARGIN || h > hi + TILETREE_MARGIN) {
            continue;
        }
        uint class_ = 0u;
        precise float dist = 0.0;
        if (h < lo) {
            class_ = 1u;
            dist = lo - h;
        } else if (h > hi) {
            class_ = 1u;
            dist = h - hi;
        }
        precise float sh = s * h;
        bool better = !found || class_ < best_class
            || (class_ == best_class && (dist < best_dist || (dist == best_dist && sh > best_sh)));
        if (better) {
            found = true;
            best_class = class_;
            best_dist = dist;
            best_sh = sh;
            best_h = h;
        }
    }
    int r1 = int(pc.resolution) - 1;
    uvec3 voxel;
    voxel[b] = uint(clamp(u, 0, r1));
    voxel[c] = uint(clamp(v, 0, r1));
    if (found) {
        voxel[a] = uint(clamp(int(floor(best_h)), 0, r1));
    } else {
        voxel[a] = uint(clamp(int(tile.origin[a] + tile.side / 2u), 0, r1));
    }
    U64Ptr(pc.keys).v[t] = morton3(voxel);
    U32Ptr(pc.filled_out).v[t] = found ? 1u : 0u;
}
