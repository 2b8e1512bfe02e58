#version 460
// Test and benchmark harness of ctree/lookup.glsl: mode 0 reads uvec4 (pos.xyz, lod) in fixed
// point and writes ctree_lookup_fixed as an int; mode 1 reads vec4 (uv.xyz, lod) and writes
// ctree_sample as a float's bits.
#include "common.glsl"
#include "ctree/lookup.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 16) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    CtreeParams tree;
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
    if (pc.mode == 0u) {
        uvec4 q = UVec4Ptr(pc.points).v[i];
        U32Ptr(pc.results).v[i] = uint(ctree_lookup_fixed(pc.tree, q.xyz, q.w));
    } else {
        vec4 q = Vec4Ptr(pc.points).v[i];
        U32Ptr(pc.results).v[i] = floatBitsToUint(ctree_sample(pc.tree, q.xyz, q.w));
    }
}
