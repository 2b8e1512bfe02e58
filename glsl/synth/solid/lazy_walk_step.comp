#version 460
// The dependency walk's bookkeeping between its dispatches, on the device so that the host
// reads no count until the walk ends (solid/lazy/walk.rs). One invocation.
// op 0, after a stage's expand (its expanding entries counted in LAZY_WALK_GROWN, which it
//   resets): the expanded length n + 18 · grown of the set whose length is at word `count`,
//   clamped to `cap` (the expanded buffer) with the overflow flagged, and the length the sort
//   orders (0 when no voxel expanded: the set is sorted already).
// op 1, after the scan of a unique pass's heads: the unique length into word `count`, clamped
//   to `cap` (the destination buffer) with the overflow flagged.
// Either op raises word `demand` to the unclamped length: the capacity a retry needs.
// op 2: the total into word `count`, as it is (a count, not a buffer's length).
// op 3: the workgroup counts (x, y, z) at word `args` of a dispatch of `width`-wide workgroups
//   over the length at word `count`; op 0 also writes those of the expanded set there.
// op 4: `cap` into word `count` (the request's length, which the host knows).
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t words;
    uint op;
    uint count;
    uint demand;
    uint cap;
    uint args;
    uint width;
} pc;

// The workgroup counts over `len` invocations into words `args`.
void write_args(U32Ptr w, uint len) {
    uvec3 g = lazy_groups(len, pc.width);
    w.v[pc.args] = g.x;
    w.v[pc.args + 1u] = g.y;
    w.v[pc.args + 2u] = g.z;
}

void main() {
    if (global_index() != 0ul) {
        return;
    }
    U32Ptr w = U32Ptr(pc.words);
    if (pc.op == 3u) {
        write_args(w, w.v[pc.count]);
        return;
    }
    if (pc.op == 4u) {
        w.v[pc.count] = pc.cap;
        return;
    }
    uint total = w.v[LAZY_WALK_TOTAL];
    if (pc.op == 0u) {
        total = w.v[LAZY_WALK_GROWN];
        w.v[LAZY_WALK_GROWN] = 0u;
    }
    if (pc.op == 2u) {
        w.v[pc.count] = total;
        return;
    }
    uint want = total;
    if (pc.op == 0u) {
        // Computed in 64 bits: 18 · total may pass 2^32 on a set past every buffer's size.
        uint64_t wide = uint64_t(w.v[pc.count]) + 18ul * uint64_t(total);
        want = uint(min(wide, 0xfffffffful));
    }
    w.v[pc.demand] = max(w.v[pc.demand], want);
    uint len = min(want, pc.cap);
    if (len < want) {
        w.v[LAZY_WALK_OVERFLOW] = 1u;
    }
    if (pc.op == 0u) {
        w.v[LAZY_WALK_EXPANDED] = len;
        w.v[LAZY_WALK_SORTED] = total == 0u ? 0u : len;
        write_args(w, len);
    } else {
        w.v[pc.count] = len;
    }
}
