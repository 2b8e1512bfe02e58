#version 460
// Perfect-hash construction, step 1 (one invocation per key): the key's point, h0 (packed) and
// bucket h1; bucket sizes and anchors (smallest key index per bucket); keys outside the
// universe reported in status.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/perfect_keys.glsl"
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys;
    uint64_t h0s;
    uint64_t buckets;
    uint64_t counts;
    uint64_t anchors;
    uint64_t status;
    uint64_t key_count;
    uint n;
    uint layout_id;
    uint dims_x;
    uint dims_y;
    uint dims_z;
    uint dimensions;
    uint axis_bits;
    uint h;
    uint phi;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t key = U64Ptr(pc.keys).v[i];
    uvec3 p;
    if (!perfect_key_point(key, pc.layout_id, uvec3(pc.dims_x, pc.dims_y, pc.dims_z), pc.dimensions, pc.axis_bits, pc.key_count, p)) {
        atomicMax(U64Ptr(pc.status).v[PERFECT_STATUS_BAD_KEY], key + 1ul);
        U32Ptr(pc.buckets).v[i] = 0xffffffffu;
        return;
    }
    uvec3 m = p % pc.phi;
    uint q = m.x + pc.phi * (m.y + pc.phi * m.z);
    U32Ptr(pc.h0s).v[i] = perfect_pack_h0(p % pc.h, pc.dimensions);
    U32Ptr(pc.buckets).v[i] = q;
    atomicAdd(U32Ptr(pc.counts).v[q], 1u);
    atomicMin(U32Ptr(pc.anchors).v[q], i);
}
