#version 460
// Test and benchmark harness of store/octree.glsl: out[i] = the nearest (mode 0), trilinear
// (mode 1) or MIP lookup at depth mode - 2 (mode >= 2) at points[i]; mode STORE_LOOKUP_SAMPLE writes the sample lookup
// (sum, then coverage and alpha gradient: out[2i], out[2i + 1]).
#include "common.glsl"
#include "store/octree.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec3Ptr { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    OctreeParams store;
    uint64_t points;
    uint64_t results;
    uint n;
    uint mode;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    vec3 pos = Vec3Ptr(pc.points).v[i];
    if (pc.mode == STORE_LOOKUP_SAMPLE) {
        StoreSample s = store_octree_sample(pc.store, pos);
        Vec4Ptr(pc.results).v[2u * i] = s.sum;
        Vec4Ptr(pc.results).v[2u * i + 1u] = vec4(s.coverage, s.gradient);
        return;
    }
    vec4 c;
    if (pc.mode == 0u) {
        c = store_octree_nearest(pc.store, pos);
    } else if (pc.mode == 1u) {
        c = store_octree_trilinear(pc.store, pos);
    } else {
        c = store_octree_mip(pc.store, pos, pc.mode - 2u);
    }
    Vec4Ptr(pc.results).v[i] = c;
}
