#version 460
// Lazy synthesis into the stores: the RGBA8 texel (red in the low byte; alpha the relief code,
// or 255 without relief) of each voxel of a sorted key set of the R^3 grid (Morton keys of its
// position), from its final triple: per byte the median of the three roles' exemplar texels
// (voxel_texel in synth/src/solid/relief.rs). A voxel that is not final counts an error.
#include "common.glsl"
#include "synth/lazy.glsl"
#include "synth/synth.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t keys;     // Morton keys of grid positions
    uint64_t rgb;      // 3 x side^2 packed texels (RGB, relief code), role after role
    uint64_t colours;  // out: RGBA8 per key
    uint64_t errors;
    uint n;
    uint level;
    uint side;
} pc;

uint median3(uint a, uint b, uint c) {
    return max(min(a, b), min(max(a, b), c));
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    ivec3 p = ivec3(morton3_decode(U64Ptr(pc.keys).v[i]));
    uint s = lazy_slot(l, p);
    if (s == HASH_NOT_FOUND || U32Ptr(l.counts).v[s] != l.stride) {
        atomicAdd(U32Ptr(pc.errors).v[0], 1u);
        return;
    }
    uvec3 t = lazy_version(l, s, l.stride - 1u);
    uint c[3];
    for (uint r = 0u; r < 3u; r++) {
        uvec2 e = synth_unpack(t[r]);
        c[r] = U32Ptr(pc.rgb).v[r * pc.side * pc.side + e.y * pc.side + e.x];
    }
    uint rgba = 0u;
    for (uint ch = 0u; ch < 4u; ch++) {
        uint sh = 8u * ch;
        rgba |= median3((c[0] >> sh) & 0xffu, (c[1] >> sh) & 0xffu, (c[2] >> sh) & 0xffu) << sh;
    }
    U32Ptr(pc.colours).v[i] = rgba;
}
