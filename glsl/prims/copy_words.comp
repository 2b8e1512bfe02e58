#version 460
// Copies n 32-bit words through descriptor bindings: the bandwidth reference of `bench prims`
// and the kernel that exercises descriptor binding.
#include "common.glsl"

layout(binding = 0, scalar) readonly buffer Src { uint src[]; };
layout(binding = 1, scalar) writeonly buffer Dst { uint dst[]; };
layout(push_constant, scalar) uniform Push { uint n; } pc;

void main() {
    uint64_t i = global_index();
    if (i < pc.n) {
        dst[uint(i)] = src[uint(i)];
    }
}
