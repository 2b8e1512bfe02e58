#version 460
// Interpolation voxels: each touched interpolation cell j (Morton key on the shifted grid)
// writes its eight corner voxels j - {0,1}^3, clamped onto the R^3 grid, to dst[8i ..].
#include "common.glsl"
#include "morton.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t dst;
    uint n;
    uint resolution;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    ivec3 j = ivec3(morton3_decode(U64Ptr(pc.cells).v[i]));
    for (int o = 0; o < 8; ++o) {
        ivec3 down = ivec3(o & 1, (o >> 1) & 1, (o >> 2) & 1);
        uvec3 voxel = uvec3(clamp(j - down, ivec3(0), ivec3(int(pc.resolution) - 1)));
        U64Ptr(pc.dst).v[8u * i + uint(o)] = morton3(voxel);
    }
}
