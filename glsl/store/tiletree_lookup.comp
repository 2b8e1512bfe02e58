#version 460
// Test and benchmark harness of store/tiletree.glsl: out[i] = the nearest (mode 0) or bilinear
// (mode 1) lookup at points[i]; mode STORE_LOOKUP_SAMPLE writes the sample lookup
// (sum, then coverage and alpha gradient: out[2i], out[2i + 1]) with normal normals[i].
#include "common.glsl"
#include "store/tiletree.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec3Ptr { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    TileTreeParams store;
    uint64_t points;
    uint64_t normals;
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
    vec3 normal = Vec3Ptr(pc.normals).v[i];
    if (pc.mode == STORE_LOOKUP_SAMPLE) {
        StoreSample s = store_tiletree_sample(pc.store, pos, normal);
        Vec4Ptr(pc.results).v[2u * i] = s.sum;
        Vec4Ptr(pc.results).v[2u * i + 1u] = vec4(s.coverage, s.gradient);
        return;
    }
    Vec4Ptr(pc.results).v[i] = pc.mode == 0u ? store_tiletree_nearest(pc.store, pos, normal)
                                             : store_tiletree_bilinear(pc.store, pos, normal);
}
