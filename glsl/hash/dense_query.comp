#version 460
// The practical limit of any lookup: results[i] = dense[keys[i]], one read per query.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t dense;
    uint64_t keys;
    uint64_t results;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i < pc.n) {
        U32Ptr(pc.results).v[i] = U32Ptr(pc.dense).v[uint(U64Ptr(pc.keys).v[i])];
    }
}
