#version 460
// Between two levels of the dependency walk: the parent (lazy key of the position halved) of
// every needed voxel with no stored version, tagged with `stage`, the level above's requested
// voxels needed final; a voxel already stored writes LAZY_NO_KEY (tagged), which sorts after
// every real key and which the unique pass drops. mode 1 instead tags plain keys, `or_bits`
// set (the requested voxels of the finest level; a texture position's Morton key becomes its
// lazy key by setting the bias bits, see solid/lazy/walk.rs), and counts in `outside` the
// keys whose position lies at or past `resolution` on an axis (0: no check). Mode 0 also
// flags in `fresh` (when not 0) the voxels the level will store that it does not hold yet, as
// lazy_prepare.comp does: the walk counts them for the host, which makes room for them. The
// length n is read on the device (count), at most `range`; the walk dispatches mode 0
// indirectly, over about n invocations (solid/lazy/walk.rs).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t src;      // mode 0: stage-tagged keys; mode 1: plain keys
    uint64_t dst;      // stage-tagged keys
    uint64_t count;    // the length n (one word)
    uint64_t outside;  // mode 1: a counter of positions outside the texture
    uint64_t fresh;    // mode 0: out, 1 for a voxel to store that is not held (or 0)
    uint64_t or_bits;  // mode 1: bits set in every key
    uint range;        // entries the buffers hold (n at most this)
    uint resolution;   // mode 1: the texture's resolution, or 0
    uint level;
    uint stage;
    uint mode;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= min(U32Ptr(pc.count).v[0], pc.range)) {
        return;
    }
    uint64_t s = U64Ptr(pc.src).v[i];
    if (pc.mode == 1u) {
        if (pc.resolution != 0u && any(greaterThanEqual(morton3_decode(s), uvec3(pc.resolution)))) {
            atomicAdd(U32Ptr(pc.outside).v[0], 1u);
        }
        U64Ptr(pc.dst).v[i] = lazy_tag(s | pc.or_bits, pc.stage);
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(s));
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    bool absent = lazy_known(l, p) == 0u;
    uint64_t parent = absent ? lazy_key(p >> 1) : LAZY_NO_KEY;
    U64Ptr(pc.dst).v[i] = lazy_tag(parent, pc.stage);
    if (pc.fresh != 0ul) {
        bool store = lazy_untag_stage(s) >= lazy_store_from(l);
        U32Ptr(pc.fresh).v[i] = absent && store ? 1u : 0u;
    }
}
