#version 460
// After a depth's correction passes: the working states of corrected pixels go back to states
// (coordinate and exemplar | level << 8 from the packed layout's texel table). Pixels flagged
// MS_FIXED or MS_ABSENT were never corrected and keep their state.
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t texel;     // working texel index per pixel
    uint64_t transfer;  // working transfer per pixel (ms_pack_transfer)
    uint64_t states;  // states of the region, updated
    uint64_t texels;    // per texel: packed coordinate, meta | offers-period flag << 16
    uint pixels;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.pixels) {
        return;
    }
    uint a = U32Ptr(pc.texel).v[i];
    if ((a & MS_FIXED) != 0u) {
        return;
    }
    uvec2 c = UVec2Ptr(pc.texels).v[a];
    ivec3 t = ms_unpack_transfer(UVec2Ptr(pc.transfer).v[i]);
    MsStates(pc.states).v[i] = MsState(c.x, c.y & 0xffffu, t.x, t.y, t.z);
}
