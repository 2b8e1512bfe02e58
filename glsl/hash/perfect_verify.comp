#version 460
// Perfect-hash construction, placement round part 2 (one invocation per listed bucket): a
// bucket that won every slot it claimed this iteration takes them (occupancy bits) and keeps
// its offset; the others stay pending (counted, and the largest pending size recorded for
// the next iteration's gate) and retry from the same candidate.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t order;
    uint64_t counts;
    uint64_t starts;
    uint64_t member_h0;
    uint64_t occupied;
    uint64_t claims;
    uint64_t state;
    uint64_t proposal;
    uint64_t offsets;
    uint64_t pending;
    uint64_t largest_pending;
    uint first;
    uint count;
    uint iteration;
    uint h;
    uint dimensions;
} pc;

void main() {
    uint idx = uint(global_index());
    if (idx >= pc.count) {
        return;
    }
    uint q = U32Ptr(pc.order).v[pc.first + idx];
    U32Ptr state = U32Ptr(pc.state);
    if (state.v[q] >= PERFECT_FAILED) {
        return;
    }
    U32Ptr proposal = U32Ptr(pc.proposal);
    uint m = U32Ptr(pc.counts).v[q];
    if (proposal.v[2u * q + 1u] != pc.iteration) {
        atomicAdd(U32Ptr(pc.pending).v[0], 1u);
        atomicMax(U32Ptr(pc.largest_pending).v[0], min(m, 63u));
        return;
    }
    uint b = U32Ptr(pc.starts).v[q];
    U32Ptr h0 = U32Ptr(pc.member_h0);
    uvec3 o = perfect_coords(proposal.v[2u * q], pc.h);
    uint64_t stamp = perfect_stamp(pc.iteration, m, q);
    for (uint j = 0u; j < m; ++j) {
        uint t = perfect_linear(perfect_add_mod(perfect_unpack_h0(h0.v[b + j], pc.dimensions), o, pc.h), pc.h);
        if (U64Ptr(pc.claims).v[t] != stamp) {
            atomicAdd(U32Ptr(pc.pending).v[0], 1u);
            atomicMax(U32Ptr(pc.largest_pending).v[0], min(m, 63u));
            return;
        }
    }
    for (uint j = 0u; j < m; ++j) {
        uint t = perfect_linear(perfect_add_mod(perfect_unpack_h0(h0.v[b + j], pc.dimensions), o, pc.h), pc.h);
        atomicOr(U32Ptr(pc.occupied).v[t >> 5], 1u << (t & 31u));
    }
    U32Ptr(pc.offsets).v[q] = proposal.v[2u * q];
    state.v[q] = PERFECT_PLACED;
}
