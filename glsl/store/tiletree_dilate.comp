#version 460
// TileTree fill, step 3: an empty texel takes the colour of the nearest filled texel of its
// row (mode 0; left first on a tie) or column (mode 1; lower first) within its tile. Reads
// filled_in, writes filled_out; only empty texels are written, only filled ones read, so one
// pass has no races. Reference: dilate in compute/src/store/tiletree/fill_cpu.rs.
#include "store/tiletree_build.glsl"

void main() {
    uint t = uint(global_index());
    if (t >= pc.n_texels) {
        return;
    }
    U32Ptr filled = U32Ptr(pc.filled_in);
    U32Ptr colours = U32Ptr(pc.colours);
    if (filled.v[t] != 0u) {
        U32Ptr(pc.filled_out).v[t] = 1u;
        return;
    }
    TileRecord tile = tiletree_tile(tiletree_tile_of(t));
    uint local = t - tile.texel_offset;
    uint pos = pc.mode == 0u ? local % tile.size.x : local / tile.size.x;
    uint step = pc.mode == 0u ? 1u : tile.size.x;
    uint len = pc.mode == 0u ? tile.size.x : tile.size.y;
    uint done = 0u;
    for (uint d = 1u; d < len; ++d) {
        uint src = 0xffffffffu;
        if (pos >= d && filled.v[t - d * step] != 0u) {
            src = t - d * step;
        } else if (pos + d < len && filled.v[t + d * step] != 0u) {
            src = t + d * step;
        }
        if (src != 0xffffffffu) {
            colours.v[t] = colours.v[src];
            done = 1u;
            break;
        }
    }
    U32Ptr(pc.filled_out).v[t] = done;
}
