#version 460
// Runs the glint point query (glint/by_example.glsl) at a batch of target points so that tests
// can compare it with its CPU twin (renderer/src/glint/by_example.rs). Each result is 10
// floats: normal (2), Jacobian (4, column-major), exact Jacobian (4).
#include "common.glsl"
#include "glint/by_example.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Points { vec2 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Results { float v[]; };

layout(push_constant, scalar) uniform Push {
    GlintMap map;
    uint64_t points;
    uint64_t results;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    GlintPoint p = glint_point(pc.map, Points(pc.points).v[i]);
    Results r = Results(pc.results);
    uint at = i * 10u;
    r.v[at] = p.normal.x;
    r.v[at + 1u] = p.normal.y;
    r.v[at + 2u] = p.jacobian[0][0];
    r.v[at + 3u] = p.jacobian[0][1];
    r.v[at + 4u] = p.jacobian[1][0];
    r.v[at + 5u] = p.jacobian[1][1];
    r.v[at + 6u] = p.jacobian_exact[0][0];
    r.v[at + 7u] = p.jacobian_exact[0][1];
    r.v[at + 8u] = p.jacobian_exact[1][0];
    r.v[at + 9u] = p.jacobian_exact[1][1];
}
