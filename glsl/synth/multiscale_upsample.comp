#version 460
// One depth of the multiscale synthesizer: each pixel inherits its parent's exemplar, moves one
// stack level finer (coordinate + spacing * child parity) or, past a leaf's finest level, is
// magnified (same texel); its transfer is the bilinear blend (9, 3, 3, 1)/16 of its 4 nearest
// parents'. Then the jitter of its absolute position at its own spacing (none when magnified).
// At depth 0: the root's level 0 at position * spacing. CPU reference:
// synth/src/multiscale/cpu.rs (upsample_jitter_multiscale).
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t parent;     // states of the parent region (unused at depth 0)
    uint64_t states;     // output states of this region
    uint64_t exemplars;  // uvec4 per exemplar: width, height, finest level, 0
    ivec2 origin;
    uvec2 size;
    ivec2 parent_origin;
    uvec2 parent_size;
    uvec2 origin_mod;    // origin mod the root's size (depth 0)
    uint root;
    uint depth;
    uint seed;
    uint strength;
    uint has_parent;
} pc;

MsState parent_at(ivec2 q) {
    uvec2 pl = uvec2(q - pc.parent_origin);
    return MsStates(pc.parent).v[pl.y * pc.parent_size.x + pl.x];
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.size.x * pc.size.y) {
        return;
    }
    uvec2 local = uvec2(i % pc.size.x, i / pc.size.x);
    ivec2 p = pc.origin + ivec2(local);
    MsState s;
    if (pc.has_parent == 0) {
        uvec4 e = UVec4Ptr(pc.exemplars).v[pc.root];
        uint h = 1u << e.z;
        uvec2 c = (((pc.origin_mod + local) % e.xy) * h) % e.xy;
        s = MsState(synth_pack(c), pc.root, 0, 0, 0);
    } else {
        ivec2 q = p >> 1;
        MsState ps = parent_at(q);
        uvec4 e = UVec4Ptr(pc.exemplars).v[ms_exemplar(ps.meta)];
        uint level = ms_level(ps.meta);
        uint coord;
        uint child;
        if (level != MS_MAGNIFIED && level < e.z) {
            uint h = 1u << (e.z - level - 1u);
            uvec2 c = (synth_unpack(ps.coord) + h * uvec2(p & 1)) % e.xy;
            coord = synth_pack(c);
            child = level + 1u;
        } else {
            coord = ps.coord;
            child = MS_MAGNIFIED;
        }
        ivec2 sd = 2 * (p & 1) - 1;
        MsState a = parent_at(q + ivec2(sd.x, 0));
        MsState b = parent_at(q + ivec2(0, sd.y));
        MsState d = parent_at(q + sd);
        int tr = (9 * ps.tr + 3 * a.tr + 3 * b.tr + d.tr + 8) >> 4;
        int tg = (9 * ps.tg + 3 * a.tg + 3 * b.tg + d.tg + 8) >> 4;
        int tb = (9 * ps.tb + 3 * a.tb + 3 * b.tb + d.tb + 8) >> 4;
        s = MsState(coord, ms_exemplar(ps.meta) | (child << 8), tr, tg, tb);
    }
    uint level = ms_level(s.meta);
    if (level != MS_MAGNIFIED) {
        uvec4 e = UVec4Ptr(pc.exemplars).v[ms_exemplar(s.meta)];
        uint h = 1u << (e.z - level);
        ivec2 j = synth_jitter(p, pc.depth, pc.seed, h, pc.strength);
        uvec2 c = synth_unpack(s.coord);
        s.coord = synth_pack(uvec2(synth_wrap(c.x, j.x, e.x), synth_wrap(c.y, j.y, e.y)));
    }
    MsStates(pc.states).v[i] = s;
}
