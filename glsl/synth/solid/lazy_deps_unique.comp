#version 460
// Unique of sorted stage-tagged keys, keeping the first entry of each key: the largest stage
// sorts first (the tag stores LAZY_STAGE_MAX − stage), so each voxel keeps the last stage it
// is needed at. write == 0: flags[i] = 1 for a first entry; write == 1 (flags scanned):
// out[flags[i]] = tagged[i] for every first entry.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t tagged;
    uint64_t flags;
    uint64_t out_keys;
    uint n;
    uint write;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t t = U64Ptr(pc.tagged).v[i];
    bool head = i == 0u || lazy_untag_key(U64Ptr(pc.tagged).v[i - 1u]) != lazy_untag_key(t);
    if (pc.write == 0u) {
        U32Ptr(pc.flags).v[i] = head ? 1u : 0u;
    } else if (head) {
        U64Ptr(pc.out_keys).v[U32Ptr(pc.flags).v[i]] = t;
    }
}
