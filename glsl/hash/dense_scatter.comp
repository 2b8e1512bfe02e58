#version 460
// The dense-array baseline: dense[keys[i]] = payloads[i] (the array was filled with
// HASH_NOT_FOUND).
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t dense;
    uint64_t keys;
    uint64_t payloads;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i < pc.n) {
        U32Ptr(pc.dense).v[uint(U64Ptr(pc.keys).v[i])] = U32Ptr(pc.payloads).v[i];
    }
}
