#version 460
// Lazy synthesis, before a level: each needed voxel's slot in the level's table, and a flag
// for the voxels to store that are not stored yet (scanned into their new slots by
// lazy_assign.comp); a voxel needed only upsampled is not stored (lazy_store_from).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;   // LazyLevel records
    uint64_t keys;     // the level's needed voxels (stage-tagged keys)
    uint64_t slots;    // out: slot, or HASH_NOT_FOUND
    uint64_t flags;    // out: 1 for a voxel not stored yet
    uint64_t work;     // out: adds the versions this request computes
    uint n;
    uint level;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    uint64_t t = U64Ptr(pc.keys).v[i];
    ivec3 p = lazy_position(lazy_untag_key(t));
    uint s = lazy_slot(l, p);
    uint stage = lazy_untag_stage(t);
    // A voxel needed only upsampled is not stored (lazy_store_from).
    bool store = stage >= lazy_store_from(l);
    U32Ptr(pc.slots).v[i] = s;
    U32Ptr(pc.flags).v[i] = s == HASH_NOT_FOUND && store ? 1u : 0u;
    uint known = s == HASH_NOT_FOUND ? 0u : U32Ptr(l.counts).v[s];
    uint needed = store ? lazy_version_at(l, stage, lazy_class(p)) + 1u : 0u;
    if (needed > known) {
        atomicAdd(U32Ptr(pc.work).v[0], needed - known);
    }
}
