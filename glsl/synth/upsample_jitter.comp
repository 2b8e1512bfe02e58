#version 460
// One pyramid level's starting point: each pixel inherits its parent's exemplar coordinate
// plus spacing * (child parity) (at level 0: position * spacing), then adds the jitter of its
// absolute position. CPU reference: synth/src/cpu.rs (upsample_jitter).
#include "common.glsl"
#include "synth/synth.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t parent;     // packed coordinates of the parent region (unused at level 0)
    uint64_t coords;     // output: packed coordinates of this region
    ivec2 origin;        // absolute position of the region's first pixel
    uvec2 size;
    ivec2 parent_origin;
    uvec2 parent_size;
    uvec2 origin_mod;    // origin mod exemplar size (level 0, avoids signed %)
    uvec2 exemplar;      // exemplar width and height
    uint spacing;
    uint level;
    uint seed;
    uint strength;
    uint has_parent;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.size.x * pc.size.y) {
        return;
    }
    uvec2 local = uvec2(i % pc.size.x, i / pc.size.x);
    ivec2 p = pc.origin + ivec2(local);
    uvec2 c;
    if (pc.has_parent == 0) {
        c = (((pc.origin_mod + local) % pc.exemplar) * pc.spacing) % pc.exemplar;
    } else {
        ivec2 q = p >> 1;
        uvec2 pl = uvec2(q - pc.parent_origin);
        c = synth_unpack(U32Ptr(pc.parent).v[pl.y * pc.parent_size.x + pl.x]);
        c = (c + pc.spacing * uvec2(p & 1)) % pc.exemplar;
    }
    ivec2 j = synth_jitter(p, pc.level, pc.seed, pc.spacing, pc.strength);
    c = uvec2(synth_wrap(c.x, j.x, pc.exemplar.x), synth_wrap(c.y, j.y, pc.exemplar.y));
    U32Ptr(pc.coords).v[i] = synth_pack(c);
}
