#version 460
// Copies n 32-bit words through device addresses, four per invocation where aligned: the
// bandwidth reference that `bench prims` measures the scan against.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t src;
    uint64_t dst;
    uint n;
} pc;

void main() {
    uint64_t q = global_index();
    uint first = uint(q) * 4u;
    if (first >= pc.n) {
        return;
    }
    if (first + 4u <= pc.n) {
        UVec4Ptr(pc.dst).v[uint(q)] = UVec4Ptr(pc.src).v[uint(q)];
    } else {
        for (uint i = first; i < pc.n; ++i) {
            U32Ptr(pc.dst).v[i] = U32Ptr(pc.src).v[i];
        }
    }
}
