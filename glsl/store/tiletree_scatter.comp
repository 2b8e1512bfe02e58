#version 460
// TileTree fill, step 4: texel t of its tile goes to the tile's place in the tile map
// (mode 0). Mode 2 reads it back before a re-plan: colours[t] = the map's texel, and keys[t]
// stays the texel's voxel where the texel met the surface (filled_in[t] != 0), else becomes
// 1 << (3 log2 R), above every voxel's key, so a sort puts it last and no search finds it.
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
    uint m = (tile.corner.y + y) * pc.map_width + tile.corner.x + x;
    if (pc.mode == 2u) {
        U32Ptr(pc.colours).v[t] = U32Ptr(pc.map).v[m];
        if (U32Ptr(pc.filled_in).v[t] == 0u) {
            U64Ptr(pc.keys).v[t] = 1ul << (3u * uint(findMSB(pc.resolution)));
        }
        return;
    }
    U32Ptr(pc.map).v[m] = U32Ptr(pc.colours).v[t];
}
