#version 460
// Perfect-hash construction, step 3 (one invocation per bucket): the histogram of bucket sizes
// (sizes >= 2, the last class collecting everything larger), the singleton flags, and the
// duplicate check (two keys of a bucket with equal h0 are the same point).
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t counts;
    uint64_t starts;
    uint64_t members;
    uint64_t member_h0;
    uint64_t keys;
    uint64_t histogram;
    uint64_t singles;
    uint64_t status;
    uint entries;
    uint classes;
} pc;

void main() {
    uint q = uint(global_index());
    if (q >= pc.entries) {
        return;
    }
    uint m = U32Ptr(pc.counts).v[q];
    U32Ptr(pc.singles).v[q] = m == 1u ? 1u : 0u;
    if (m < 2u) {
        return;
    }
    atomicAdd(U32Ptr(pc.histogram).v[min(m, pc.classes - 1u)], 1u);
    uint b = U32Ptr(pc.starts).v[q];
    U32Ptr h0 = U32Ptr(pc.member_h0);
    for (uint j = 1u; j < m; ++j) {
        uint hj = h0.v[b + j];
        for (uint i = 0u; i < j; ++i) {
            if (h0.v[b + i] == hj) {
                atomicAdd(U64Ptr(pc.status).v[PERFECT_STATUS_DUPLICATES], 1ul);
                uint64_t key = U64Ptr(pc.keys).v[U32Ptr(pc.members).v[b + j]];
                atomicMin(U64Ptr(pc.status).v[PERFECT_STATUS_DUPLICATE_KEY], key);
                break;
            }
        }
    }
}
