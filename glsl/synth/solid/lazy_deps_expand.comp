#version 460
// One backward step of the dependency walk (synth/src/solid/lazy/deps.rs), over the
// stage-tagged keys of one level: a voxel needed after a stage that corrects its class (cls,
// or every class on a parallel level) whose version from that stage is not stored yet needs
// its 18 plane neighbours after stage − 1.
// write == 0: flags[i] = 1 for such a voxel. write == 1 (flags scanned into offsets): out[i]
// = tagged[i], and the expanding voxel's neighbours go to out[n + 18 · offsets[i] + j],
// tagged with stage − 1. A neighbour outside the table's extent counts an error.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t tagged;   // the level's needed voxels, sorted stage-tagged keys
    uint64_t flags;    // write 0: out; write 1: the exclusive scan of the flags
    uint64_t out_keys; // write 1: n + 18 · expanding entries
    uint64_t errors;
    uint n;
    uint level;
    uint stage;
    uint cls;          // the class place the stage corrects, or LAZY_ALL_CLASSES
    uint version;      // the version subpass `stage` produces
    uint write;
} pc;

const ivec3 PLANE_NEIGHBOURS[18] = ivec3[18](
    ivec3(0, -1, -1), ivec3(-1, 0, -1), ivec3(0, 0, -1), ivec3(1, 0, -1), ivec3(0, 1, -1),
    ivec3(-1, -1, 0), ivec3(0, -1, 0), ivec3(1, -1, 0), ivec3(-1, 0, 0), ivec3(1, 0, 0),
    ivec3(-1, 1, 0), ivec3(0, 1, 0), ivec3(1, 1, 0), ivec3(0, -1, 1), ivec3(-1, 0, 1),
    ivec3(0, 0, 1), ivec3(1, 0, 1), ivec3(0, 1, 1));

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t t = U64Ptr(pc.tagged).v[i];
    ivec3 p = lazy_position(lazy_untag_key(t));
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    bool expand = lazy_untag_stage(t) >= pc.stage && lazy_corrects(pc.cls, lazy_class(p))
        && lazy_known(l, p) <= pc.version;
    if (pc.write == 0u) {
        U32Ptr(pc.flags).v[i] = expand ? 1u : 0u;
        return;
    }
    U64Ptr(pc.out_keys).v[i] = t;
    if (!expand) {
        return;
    }
    uint base = pc.n + 18u * U32Ptr(pc.flags).v[i];
    for (uint j = 0u; j < 18u; j++) {
        ivec3 q = p + PLANE_NEIGHBOURS[j];
        if (!lazy_inside(l, q)) {
            atomicAdd(U32Ptr(pc.errors).v[0], 1u);
        }
        U64Ptr(pc.out_keys).v[base + j] = lazy_tag(lazy_key(q), pc.stage - 1u);
    }
}
