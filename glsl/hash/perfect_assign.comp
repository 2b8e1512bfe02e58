#version 460
// Perfect-hash construction, singletons part 2 (one invocation per occupancy word): the r-th
// free slot (in slot order) goes to the r-th single-key bucket (in bucket order), so no
// search and no conflict remains; deterministic.
#include "common.glsl"
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t occupied;
    uint64_t free_ranks;
    uint64_t singles;
    uint64_t single_count;
    uint64_t anchors;
    uint64_t h0s;
    uint64_t offsets;
    uint words;
    uint slots;
    uint h;
    uint dimensions;
} pc;

void main() {
    uint w = uint(global_index());
    if (w >= pc.words) {
        return;
    }
    uint valid = pc.slots - 32u * w >= 32u ? 0xffffffffu : (1u << (pc.slots - 32u * w)) - 1u;
    uint free_bits = ~U32Ptr(pc.occupied).v[w] & valid;
    uint rank = U32Ptr(pc.free_ranks).v[w];
    uint total = U32Ptr(pc.single_count).v[0];
    while (free_bits != 0u && rank < total) {
        uint bit = uint(findLSB(free_bits));
        free_bits &= free_bits - 1u;
        uint q = U32Ptr(pc.singles).v[rank];
        uvec3 anchor = perfect_unpack_h0(U32Ptr(pc.h0s).v[U32Ptr(pc.anchors).v[q]], pc.dimensions);
        uvec3 o = (perfect_coords(32u * w + bit, pc.h) + pc.h - anchor) % pc.h;
        U32Ptr(pc.offsets).v[q] = perfect_linear(o, pc.h);
        ++rank;
    }
}
