#version 460
// Before a depth's correction passes: each pixel's state (coordinate, exemplar, level,
// transfer) becomes its working state, the texel index of its stack level in the depth set's
// packed layout (synth/src/multiscale/atlas.rs) and the packed transfer. A magnified pixel
// gets its leaf's finest texel, flagged MS_FIXED; a level absent from the set the zero texel
// (after the last), flagged too. A pixel at a level offering candidates that can be
// period-penalized sets control word 0.
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t states;     // states of the region
    uint64_t texel;      // output: working texel index per pixel
    uint64_t transfer;   // output: working transfer per pixel (ms_pack_transfer)
    uint64_t exemplars;  // uvec4 per exemplar: width, height, finest level, 0
    uint64_t lookup;     // first texel of exemplar * 16 + level | MS_OFFERS_PERIOD, or MS_ABSENT
    uint64_t control;    // MS_CONTROL_WORDS words (multiscale.glsl)
    uint pixels;
    uint zero_texel;     // index of the zero texel
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.pixels) {
        return;
    }
    MsState s = MsStates(pc.states).v[i];
    uint ex = ms_exemplar(s.meta);
    uint level = ms_level(s.meta);
    uvec4 e = UVec4Ptr(pc.exemplars).v[ex];
    uint first = U32Ptr(pc.lookup).v[ex * MS_LEVEL_SLOTS + min(level, e.z)];
    uint a = MS_FIXED | pc.zero_texel;
    if (first != MS_ABSENT) {
        uvec2 c = synth_unpack(s.coord);
        a = (first & ~MS_OFFERS_PERIOD) + c.y * e.x + c.x;
        if (level == MS_MAGNIFIED) {
            a |= MS_FIXED;
        } else if ((first & MS_OFFERS_PERIOD) != 0u) {
            atomicOr(U32Ptr(pc.control).v[0], 1u);
        }
    }
    U32Ptr(pc.texel).v[i] = a;
    UVec2Ptr(pc.transfer).v[i] = ms_pack_transfer(ivec3(s.tr, s.tg, s.tb));
}
