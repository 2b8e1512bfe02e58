#version 460
// Lazy synthesis, before a level: each voxel not stored yet takes slot base + its rank among
// them (the exclusive scan of lazy_prepare.comp's flags) and becomes an entry to insert.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t keys;
    uint64_t slots;        // in/out
    uint64_t offsets;      // exclusive scan of the flags
    uint64_t new_keys;     // out: table keys of the new voxels
    uint64_t new_payloads; // out: their slots
    uint n;
    uint level;
    uint base;             // slots already used
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n || U32Ptr(pc.slots).v[i] != HASH_NOT_FOUND) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    if (lazy_untag_stage(U64Ptr(pc.keys).v[i]) < lazy_store_from(l)) {
        return;
    }
    uint rank = U32Ptr(pc.offsets).v[i];
    uint s = pc.base + rank;
    U32Ptr(pc.slots).v[i] = s;
    U64Ptr(pc.new_keys).v[rank] = lazy_table_key(l, lazy_position(lazy_untag_key(U64Ptr(pc.keys).v[i])));
    U32Ptr(pc.new_payloads).v[rank] = s;
}
