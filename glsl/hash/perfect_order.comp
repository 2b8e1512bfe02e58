#version 460
// Perfect-hash construction, step 4 (one invocation per bucket): buckets of >= 2 keys listed
// by decreasing size class (class starts computed on the host from the histogram). The order
// inside a class varies between runs; placement depends only on the bucket ids.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t counts;
    uint64_t class_start;
    uint64_t class_cursor;
    uint64_t order;
    uint entries;
    uint classes;
} pc;

void main() {
    uint q = uint(global_index());
    if (q >= pc.entries) {
        return;
    }
    uint m = U32Ptr(pc.counts).v[q];
    if (m < 2u) {
        return;
    }
    uint c = min(m, pc.classes - 1u);
    uint at = U32Ptr(pc.class_start).v[c] + atomicAdd(U32Ptr(pc.class_cursor).v[c], 1u);
    U32Ptr(pc.order).v[at] = q;
}
