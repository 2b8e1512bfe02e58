#version 460
// Copies n uvec4 through descriptor bindings: the plain copy a user would write, and the
// fastest one on lavapipe. Buffers over maxStorageBufferRange are copied in bound ranges.
#include "common.glsl"

layout(binding = 0, scalar) readonly buffer Src { uvec4 src[]; };
layout(binding = 1, scalar) writeonly buffer Dst { uvec4 dst[]; };
layout(push_constant, scalar) uniform Push { uint n; } pc;

void main() {
    uint64_t i = global_index();
    if (i < pc.n) {
        dst[uint(i)] = src[uint(i)];
    }
}
