#version 460
// dst[i] = marble_rgba8(voxel of keys[i]): fills a store's colours on the GPU.
#include "common.glsl"
#include "morton.glsl"
#include "store/marble.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys;
    uint64_t dst;
    uint n;
    uint resolution;
    uint seed;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uvec3 voxel = morton3_decode(U64Ptr(pc.keys).v[i]);
    U32Ptr(pc.dst).v[i] = marble_rgba8(voxel, pc.resolution, pc.seed);
}
