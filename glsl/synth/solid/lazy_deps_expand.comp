#version 460
// One backward step of the dependency walk (synth/src/solid/lazy/deps.rs), over the
// stage-tagged keys of one level: a voxel needed after a stage that corrects its class (cls,
// or every class on a parallel level) whose version from that stage is not stored yet needs
// its 18 plane neighbours after stage − 1.
// out[i] = tagged[i], and each expanding voxel claims 18 places past n with an atomic counter
// (`grown`, which lazy_walk_step.comp reads and resets) for its neighbours, tagged with
// stage − 1: the expanded set is sorted next, so the places' order does not matter. Nothing is
// written at or past `cap` (lazy_walk_step.comp flags the overflow). A neighbour outside the
// table's extent counts an error. The set's length n is read on the device (count), at most
// `range` (the set's buffer); the walk dispatches it indirectly, over about n invocations
// (solid/lazy/walk.rs).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t tagged;   // the level's needed voxels, sorted stage-tagged keys
    uint64_t out_keys; // the expanded set: n kept entries, then 18 per expanding entry
    uint64_t errors;
    uint64_t count;    // the set's length n (one word)
    uint64_t grown;    // the expanding entries' counter (one word, 0 before the dispatch)
    uint range;        // entries the set's buffer holds (n at most this)
    uint cap;          // entries out_keys holds
    uint level;
    uint stage;
    uint cls;          // the class place the stage corrects, or LAZY_ALL_CLASSES
    uint version;      // the version subpass `stage` produces
} pc;

const ivec3 PLANE_NEIGHBOURS[18] = ivec3[18](
    ivec3(0, -1, -1), ivec3(-1, 0, -1), ivec3(0, 0, -1), ivec3(1, 0, -1), ivec3(0, 1, -1),
    ivec3(-1, -1, 0), ivec3(0, -1, 0), ivec3(1, -1, 0), ivec3(-1, 0, 0), ivec3(1, 0, 0),
    ivec3(-1, 1, 0), ivec3(0, 1, 0), ivec3(1, 1, 0), ivec3(0, -1, 1), ivec3(-1, 0, 1),
    ivec3(0, 0, 1), ivec3(1, 0, 1), ivec3(0, 1, 1));

void main() {
    uint i = uint(global_index());
    uint n = min(U32Ptr(pc.count).v[0], pc.range);
    if (i >= n) {
        return;
    }
    uint64_t t = U64Ptr(pc.tagged).v[i];
    ivec3 p = lazy_position(lazy_untag_key(t));
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    bool expand = lazy_untag_stage(t) >= pc.stage && lazy_corrects(pc.cls, lazy_class(p))
        && lazy_known(l, p) <= pc.version;
    if (i < pc.cap) {
        U64Ptr(pc.out_keys).v[i] = t;
    }
    if (!expand) {
        return;
    }
    uint base = n + 18u * atomicAdd(U32Ptr(pc.grown).v[0], 1u);
    for (uint j = 0u; j < 18u; j++) {
        ivec3 q = p + PLANE_NEIGHBOURS[j];
        if (!lazy_inside(l, q)) {
            atomicAdd(U32Ptr(pc.errors).v[0], 1u);
        }
        if (base + j < pc.cap) {
            U64Ptr(pc.out_keys).v[base + j] = lazy_tag(lazy_key(q), pc.stage - 1u);
        }
    }
}
