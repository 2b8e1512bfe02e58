#version 460
// Trilinear lookups in a blocked perfect hash: results[i] = the filtered RGBA of positions[i]
// (object space, [0,1]^3), through glsl/include/hash/perfect_blocked.glsl.
#include "common.glsl"
#include "hash/perfect.glsl"
#include "hash/perfect_blocked.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec3Ptr { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    PerfectHashParams table;
    uint64_t positions;
    uint64_t results;
    uint n;
    uint block;
    uint resolution;
} pc;

void main() {
    uint i = uint(global_index());
    if (i < pc.n) {
        Vec4Ptr(pc.results).v[i] = perfect_blocked_trilinear(pc.table, pc.block, pc.resolution, Vec3Ptr(pc.positions).v[i]);
    }
}
