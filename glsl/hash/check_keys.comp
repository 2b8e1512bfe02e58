#version 460
// Key validation over keys sorted by their low bits: counters (u64) receive
//   [0] the number of i with sorted[i] == sorted[i - 1], [1] the smallest such key,
//   [2] the number of keys >= key_count (outside the universe), [3] the largest of them.
// Every element is visited, so keys outside the universe are caught wherever the sort put them.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require

layout(push_constant, scalar) uniform Push {
    uint64_t sorted;
    uint64_t counters;
    uint64_t key_count;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U64Ptr sorted = U64Ptr(pc.sorted);
    U64Ptr counters = U64Ptr(pc.counters);
    uint64_t k = sorted.v[i];
    if (k >= pc.key_count) {
        atomicAdd(counters.v[2], 1ul);
        atomicMax(counters.v[3], k);
    }
    if (i > 0u && k == sorted.v[i - 1u]) {
        atomicAdd(counters.v[0], 1ul);
        atomicMin(counters.v[1], k);
    }
}
