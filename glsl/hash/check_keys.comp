#version 460
// Key validation over keys sorted by their low bits: counters (u64) receive
//   [0] the number of i with sorted[i] == sorted[i - 1], [1] the smallest such key,
//   [2] the number of keys outside (>= key_count, or with resolution > 0 a Morton key whose
//   voxel has a coordinate >= resolution or whose bit 63 is set), [3] the largest of them,
//   [4] the smallest of them.
// Every element is visited, so keys outside are caught wherever the sort put them.
#include "common.glsl"
#include "morton.glsl"
#extension GL_EXT_shader_atomic_int64 : require

layout(push_constant, scalar) uniform Push {
    uint64_t sorted;
    uint64_t counters;
    uint64_t key_count;
    uint n;
    uint resolution;  // 0: the universe check alone
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U64Ptr sorted = U64Ptr(pc.sorted);
    U64Ptr counters = U64Ptr(pc.counters);
    uint64_t k = sorted.v[i];
    bool outside = k >= pc.key_count;
    if (pc.resolution > 0u) {
        uvec3 v = morton3_decode(k);
        outside = outside || (k >> 63) != 0ul || any(greaterThanEqual(v, uvec3(pc.resolution)));
    }
    if (outside) {
        atomicAdd(counters.v[2], 1ul);
        atomicMax(counters.v[3], k);
        atomicMin(counters.v[4], k);
    }
    if (i > 0u && k == sorted.v[i - 1u]) {
        atomicAdd(counters.v[0], 1ul);
        atomicMin(counters.v[1], k);
    }
}
