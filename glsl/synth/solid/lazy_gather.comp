#version 460
// Lazy synthesis, after a request: the final triple of each requested voxel.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t keys;     // requested voxels (lazy keys)
    uint64_t triples;  // out: 3 words per voxel
    uint64_t errors;   // out: counts voxels missing or not final (must stay 0)
    uint n;
    uint level;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    uint s = lazy_slot(l, lazy_position(U64Ptr(pc.keys).v[i]));
    if (s == HASH_NOT_FOUND || U32Ptr(l.counts).v[s] != l.stride) {
        atomicAdd(U32Ptr(pc.errors).v[0], 1u);
        return;
    }
    uvec3 t = lazy_version(l, s, l.stride - 1u);
    U32Ptr(pc.triples).v[i * 3u] = t.x;
    U32Ptr(pc.triples).v[i * 3u + 1u] = t.y;
    U32Ptr(pc.triples).v[i * 3u + 2u] = t.z;
}
