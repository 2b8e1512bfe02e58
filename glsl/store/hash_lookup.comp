#version 460
// Test and benchmark harness of store/hash.glsl: out[i] = the nearest (mode 0) or trilinear
// (mode 1) lookup at points[i]; mode STORE_LOOKUP_SAMPLE writes the sample lookup
// (sum, then coverage and alpha gradient: out[2i], out[2i + 1]).
#include "common.glsl"
#include "store/hash.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Vec3Ptr { vec3 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    HashStoreParams store;
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
        StoreSample s = store_hash_sample(pc.store, pos);
        Vec4Ptr(pc.results).v[2u * i] = s.sum;
        Vec4Ptr(pc.results).v[2u * i + 1u] = vec4(s.coverage, s.gradient);
        return;
    }
    Vec4Ptr(pc.results).v[i] = pc.mode == 0u ? store_hash_nearest(pc.store, pos) : store_hash_trilinear(pc.store, pos);
}
