#version 460
// Lazy synthesis, stage 0 of a level: each stored voxel with no version yet gets version 0
// (synth/lazy_upsample.glsl: its parent's final triple moved by the child offset and the
// jitter). CPU reference: upsample_voxel in synth/src/solid/cpu.rs.
#include "common.glsl"
#include "synth/lazy.glsl"
#include "synth/lazy_upsample.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t keys;
    uint64_t slots;
    uint64_t errors;   // out: counts voxels whose parent is missing (must stay 0)
    uint n;
    uint level;
    uint side;
    uint spacing;
    uint seed;
    uint strength;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    uint s = U32Ptr(pc.slots).v[i];
    // A voxel read only as upsampled has no slot: its readers compute it in place.
    if (s == HASH_NOT_FOUND || U32Ptr(l.counts).v[s] != 0u) {
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(U64Ptr(pc.keys).v[i]));
    uvec3 out_t;
    if (!lazy_upsampled(pc.levels, pc.level, p, pc.side, pc.spacing, pc.seed, pc.strength, out_t)) {
        atomicAdd(U32Ptr(pc.errors).v[0], 1u);
        return;
    }
    lazy_store(l, s, 0u, out_t);
    U32Ptr(l.counts).v[s] = 1u;
}
