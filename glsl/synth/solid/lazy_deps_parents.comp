#version 460
// After a level's dependency walk: the parent (lazy key of the position halved) of every
// needed voxel with no stored version, the level above's requested voxels; a voxel already
// stored writes LAZY_NO_KEY, which sorts after every real key and is dropped. mode 1 instead
// tags plain keys with `stage` (the requested voxels of a level, needed final).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t src;      // mode 0: stage-tagged keys; mode 1: plain keys
    uint64_t dst;      // mode 0: plain keys; mode 1: stage-tagged keys
    uint n;
    uint level;
    uint stage;
    uint mode;
} pc;

const uint64_t LAZY_NO_KEY = (1ul << 57) - 1ul;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t s = U64Ptr(pc.src).v[i];
    if (pc.mode == 1u) {
        U64Ptr(pc.dst).v[i] = lazy_tag(s, pc.stage);
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(s));
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    U64Ptr(pc.dst).v[i] = lazy_known(l, p) == 0u ? lazy_key(p >> 1) : LAZY_NO_KEY;
}
