#version 460
// Before a correction subpass of a depth whose set has candidates that can be
// period-penalized: chooses the kernel on the device. While no pixel sits at a level offering
// such candidates (control word 0, kept by multiscale_enter.comp and the corrections without the
// test), the correction without the period test gets the workgroups and the one with it none;
// after, the reverse. So a loop graph, whose depth sets keep the coarsest levels, runs the test
// only where pixels are there. One invocation.
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t control;  // MS_CONTROL_WORDS words (multiscale.glsl)
    uvec3 groups;      // workgroups of the subpass
} pc;

void main() {
    if (global_index() != 0) {
        return;
    }
    bool period = U32Ptr(pc.control).v[0] != 0u;
    uvec3 none = uvec3(0u, 1u, 1u);
    uvec3 plain = period ? none : pc.groups;
    uvec3 tested = period ? pc.groups : none;
    for (int j = 0; j < 3; j++) {
        U32Ptr(pc.control).v[1 + j] = plain[j];
        U32Ptr(pc.control).v[4 + j] = tested[j];
    }
    U32Ptr(pc.control).v[7] += period ? 1u : 0u;
}
