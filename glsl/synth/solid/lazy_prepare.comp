#version 460
// Lazy synthesis, before a level: each needed voxel's slot in the level's table, and a flag
// for the voxels not stored yet (scanned into their new slots by lazy_assign.comp).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;   // LazyLevel records
    uint64_t keys;     // the level's needed voxels (lazy keys)
    uint64_t slots;    // out: slot, or HASH_NOT_FOUND
    uint64_t flags;    // out: 1 for a voxel not stored yet
    uint n;
    uint level;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    uint s = lazy_slot(l, lazy_position(U64Ptr(pc.keys).v[i]));
    U32Ptr(pc.slots).v[i] = s;
    U32Ptr(pc.flags).v[i] = s == HASH_NOT_FOUND ? 1u : 0u;
}
