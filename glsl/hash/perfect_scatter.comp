#version 460
// Perfect-hash construction, step 2 (one invocation per key): each key's index and packed h0
// written into its bucket's range (starts from a scan of the sizes). The order inside a bucket
// varies between runs; nothing downstream depends on it.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t buckets;
    uint64_t h0s;
    uint64_t starts;
    uint64_t cursor;
    uint64_t members;
    uint64_t member_h0;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint q = U32Ptr(pc.buckets).v[i];
    if (q == 0xffffffffu) {
        return;
    }
    uint at = U32Ptr(pc.starts).v[q] + atomicAdd(U32Ptr(pc.cursor).v[q], 1u);
    U32Ptr(pc.members).v[at] = i;
    U32Ptr(pc.member_h0).v[at] = U32Ptr(pc.h0s).v[i];
}
