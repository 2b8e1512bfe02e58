#version 460
// Unique of sorted stage-tagged keys, keeping the first entry of each key: the largest stage
// sorts first (the tag stores LAZY_STAGE_MAX − stage), so each voxel keeps the last stage it
// is needed at; LAZY_NO_KEY (a voxel with no parent to request) is dropped. The length n is
// read on the device (count), at most `range`; the walk dispatches it indirectly, over about n
// invocations (solid/lazy/walk.rs). write == 0: flags[i] = 1 for a first entry;
// write == 1 (flags scanned): out[flags[i]] = tagged[i] for every first entry below `cap`
// (the walk's count kernel has flagged the overflow).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t tagged;
    uint64_t flags;
    uint64_t out_keys;
    uint64_t count;    // the length n (one word)
    uint range;        // entries the buffer holds (n at most this)
    uint cap;          // write 1: entries out_keys holds
    uint write;
} pc;

void main() {
    uint i = uint(global_index());
    uint n = min(U32Ptr(pc.count).v[0], pc.range);
    if (i >= n) {
        return;
    }
    uint64_t t = U64Ptr(pc.tagged).v[i];
    uint64_t k = lazy_untag_key(t);
    bool head = k != LAZY_NO_KEY
        && (i == 0u || lazy_untag_key(U64Ptr(pc.tagged).v[i - 1u]) != k);
    if (pc.write == 0u) {
        U32Ptr(pc.flags).v[i] = head ? 1u : 0u;
    } else if (head) {
        uint at = U32Ptr(pc.flags).v[i];
        if (at < pc.cap) {
            U64Ptr(pc.out_keys).v[at] = t;
        }
    }
}
