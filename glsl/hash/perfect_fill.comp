#version 460
// Perfect-hash construction, final part 2 (one invocation per key): the payload (and, for
// unconstrained access, the tag 1 + h1(p)) written at the key's slot.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/perfect_build.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t buckets;
    uint64_t h0s;
    uint64_t offsets;
    uint64_t payloads;
    uint64_t data;
    uint64_t tags;
    uint64_t status;
    uint n;
    uint h;
    uint dimensions;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint q = U32Ptr(pc.buckets).v[i];
    uvec3 o = perfect_coords(U32Ptr(pc.offsets).v[q], pc.h);
    uint t = perfect_linear(perfect_add_mod(perfect_unpack_h0(U32Ptr(pc.h0s).v[i], pc.dimensions), o, pc.h), pc.h);
    uint payload = U32Ptr(pc.payloads).v[i];
    U32Ptr(pc.data).v[t] = payload;
    if (pc.tags != 0ul) {
        U32Ptr(pc.tags).v[t] = q + 1u;
        if (payload == HASH_NOT_FOUND) {
            atomicAdd(U64Ptr(pc.status).v[PERFECT_STATUS_BAD_PAYLOAD], 1ul);
        }
    }
}
