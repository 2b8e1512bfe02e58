#version 460
// Perfect-hash construction, singletons part 1 (one invocation per occupancy word): free slots
// per word, scanned afterwards into each word's first free-slot rank.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t occupied;
    uint64_t free_counts;
    uint words;
    uint slots;
} pc;

void main() {
    uint w = uint(global_index());
    if (w >= pc.words) {
        return;
    }
    uint valid = pc.slots - 32u * w >= 32u ? 0xffffffffu : (1u << (pc.slots - 32u * w)) - 1u;
    U32Ptr(pc.free_counts).v[w] = bitCount(~U32Ptr(pc.occupied).v[w] & valid);
}
