#version 460
// Lazy synthesis, before a level: each needed voxel's slot in the level's table, and a flag
// for the voxels to store that are not stored yet (scanned into their new slots by
// lazy_assign.comp); a voxel needed only upsampled is not stored (lazy_store_from). It also
// writes each voxel's place in the order lazy_correct.comp visits them (sorted on these keys,
// stably): the voxels with work first, by class on an ordered level, needed at the latest
// stage first. A stage then runs its voxels side by side in whole SIMD groups, where in key
// order a group of eight neighbours holds one voxel of each class and runs at an eighth of
// its width.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;   // LazyLevel records
    uint64_t keys;     // the level's needed voxels (stage-tagged keys)
    uint64_t slots;    // out: slot, or HASH_NOT_FOUND
    uint64_t flags;    // out: 1 for a voxel not stored yet
    uint64_t work;     // out: adds the versions this request computes
    uint64_t order_keys; // out: the voxel's visiting key (LAZY_ORDER_BITS bits)
    uint64_t order;    // out: the voxel's index, sorted on order_keys afterwards
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
    uint cls = l.parallel != 0u ? 0u : lazy_class(p);
    uint idle = needed > known ? 0u : 1u;
    U32Ptr(pc.order_keys).v[i] = lazy_order_key(idle, cls, stage);
    U32Ptr(pc.order).v[i] = i;
}
