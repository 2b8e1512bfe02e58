#version 460
// Perfect-hash construction, placement round part 1 (one invocation per listed bucket): every
// unplaced bucket continues its search (the CPU reference's order: slots for its anchor from
// search_start(q), occupied ones skipped a bitset word at a time) for an offset that sends all
// its keys to slots free at the start of this iteration, then claims those slots with a 64-bit
// atomicMax of perfect_stamp(iteration, size, q): within an iteration the largest bucket, then
// the smallest bucket id, wins a slot, and a later iteration's claims supersede stale ones
// without any clearing pass. Buckets smaller than the largest one left pending by the last
// iteration wait, so sizes are placed strictly in decreasing order as on the CPU.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t order;
    uint64_t counts;
    uint64_t starts;
    uint64_t anchors;
    uint64_t h0s;
    uint64_t member_h0;
    uint64_t occupied;
    uint64_t claims;
    uint64_t state;
    uint64_t proposal;
    uint64_t status;
    uint64_t largest_pending;
    uint first;
    uint count;
    uint iteration;
    uint h;
    uint slots;
    uint dimensions;
    uint budget;
} pc;

void main() {
    uint idx = uint(global_index());
    if (idx >= pc.count) {
        return;
    }
    uint q = U32Ptr(pc.order).v[pc.first + idx];
    U32Ptr state = U32Ptr(pc.state);
    uint k = state.v[q];
    if (k >= PERFECT_FAILED) {
        return;
    }
    uint m = U32Ptr(pc.counts).v[q];
    if (min(m, 63u) < U32Ptr(pc.largest_pending).v[0]) {
        // A larger bucket is still unplaced: keep the greedy order (largest first).
        return;
    }
    uint b = U32Ptr(pc.starts).v[q];
    U32Ptr occupied = U32Ptr(pc.occupied);
    U32Ptr h0 = U32Ptr(pc.member_h0);
    uvec3 anchor = perfect_unpack_h0(U32Ptr(pc.h0s).v[U32Ptr(pc.anchors).v[q]], pc.dimensions);
    uvec3 minus_anchor = (pc.h - anchor) % pc.h;
    uint s0 = perfect_search_start(q, pc.slots);
    uint tested = 0u;
    bool found = false;
    uvec3 o = uvec3(0u);
    while (k < pc.slots && tested < pc.budget) {
        ++tested;
        uint s = s0 + k;
        if (s >= pc.slots) {
            s -= pc.slots;
        }
        uint word = occupied.v[s >> 5] >> (s & 31u);
        if ((word & 1u) != 0u) {
            uint inverse = ~word;
            uint run = inverse == 0u ? 32u : uint(findLSB(inverse));
            k += min(run, pc.slots - s);
            continue;
        }
        o = perfect_add_mod(perfect_coords(s, pc.h), minus_anchor, pc.h);
        bool fits = true;
        for (uint j = 0u; j < m; ++j) {
            uint t = perfect_linear(perfect_add_mod(perfect_unpack_h0(h0.v[b + j], pc.dimensions), o, pc.h), pc.h);
            if (((occupied.v[t >> 5] >> (t & 31u)) & 1u) != 0u) {
                fits = false;
                break;
            }
        }
        if (fits) {
            found = true;
            break;
        }
        ++k;
    }
    if (k >= pc.slots) {
        state.v[q] = PERFECT_FAILED;
        atomicAdd(U64Ptr(pc.status).v[PERFECT_STATUS_FAILED], 1ul);
        atomicMin(U64Ptr(pc.status).v[PERFECT_STATUS_FAILED_BUCKET], uint64_t(q));
        return;
    }
    state.v[q] = k;
    if (!found) {
        return;
    }
    U32Ptr proposal = U32Ptr(pc.proposal);
    proposal.v[2u * q] = perfect_linear(o, pc.h);
    proposal.v[2u * q + 1u] = pc.iteration;
    uint64_t stamp = perfect_stamp(pc.iteration, m, q);
    for (uint j = 0u; j < m; ++j) {
        uint t = perfect_linear(perfect_add_mod(perfect_unpack_h0(h0.v[b + j], pc.dimensions), o, pc.h), pc.h);
        atomicMax(U64Ptr(pc.claims).v[t], stamp);
    }
}
