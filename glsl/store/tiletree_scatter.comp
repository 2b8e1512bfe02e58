#version 460
// TileTree fill, step 4: texel t of its tile goes to the tile's place in the tile map.
#include "store/tiletree_build.glsl"

void main() {
    uint t = uint(global_index());
    if (t >= pc.n_texels) {
        return;
    }
    TileRecord tile = tiletree_tile(tiletree_tile_of(t));
    uint stored = tile.side + 2u;
    uint local = t - tile.texel_offset;
    uint x = local % stored;
    uint y = local / stored;
    U32Ptr(pc.map).v[(tile.corner.y + y) * pc.map_width + tile.corner.x + x] = U32Ptr(pc.colours).v[t];
}
