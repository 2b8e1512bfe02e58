#version 460
// Lazy synthesis, stage 0 of a level: each needed voxel with no version yet inherits its
// parent's final triple (found in the level above's table) moved by spacing times the child
// offset projected into each role (level 0: the projection of the position times the
// spacing), then moves by the projected 3D jitter. Exactly upsample_jitter.comp per voxel;
// CPU reference: upsample_voxel in synth/src/solid/cpu.rs.
#include "common.glsl"
#include "synth/lazy.glsl"
#include "synth/solid.glsl"

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
    if (U32Ptr(l.counts).v[s] != 0u) {
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(U64Ptr(pc.keys).v[i]));
    uint t[3];
    if (pc.level == 0u) {
        uvec3 q = ((uvec3(p & int(pc.side - 1u))) * pc.spacing) % pc.side;
        t[0] = synth_pack(q.yz);
        t[1] = synth_pack(q.xz);
        t[2] = synth_pack(q.xy);
    } else {
        LazyLevel above = LazyLevels(pc.levels).v[pc.level - 1u];
        uint ps = lazy_slot(above, p >> 1);
        if (ps == HASH_NOT_FOUND) {
            atomicAdd(U32Ptr(pc.errors).v[0], 1u);
            return;
        }
        uvec3 parent = lazy_version(above, ps, above.stride - 1u);
        ivec3 child = (p & 1) * int(pc.spacing);
        for (uint r = 0; r < 3; r++) {
            t[r] = solid_moved(parent[r], solid_project(r, child), pc.side);
        }
    }
    ivec3 j = solid_jitter(p, pc.level, pc.seed, pc.spacing, pc.strength);
    uvec3 out_t;
    for (uint r = 0; r < 3; r++) {
        out_t[r] = solid_moved(t[r], solid_project(r, j), pc.side);
    }
    lazy_store(l, s, 0u, out_t);
    U32Ptr(l.counts).v[s] = 1u;
}
