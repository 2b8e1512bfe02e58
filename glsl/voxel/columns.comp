#version 460
// Voxelization, step 1: one invocation per triangle counts its columns, the cells of its
// bounding box projected along the dominant normal axis.
#extension GL_EXT_shader_atomic_int64 : require
#include "common.glsl"
#include "voxel/grid.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t positions;
    uint64_t triangles;
    uint64_t counts;
    uint64_t total;
    uint n_triangles;
    uint extent;
    float r;
    float shift;
} pc;

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Total64 { uint64_t v; };

void main() {
    uint t = uint(global_index());
    if (t >= pc.n_triangles) {
        return;
    }
    Triangle tri = load_triangle(pc.positions, pc.triangles, t);
    ivec3 first, last;
    cell_range(tri, pc.r, pc.shift, pc.extent, first, last);
    int w = dominant_axis(tri);
    int u = (w + 1) % 3;
    int v = (w + 2) % 3;
    uint columns = uint(last[u] - first[u] + 1) * uint(last[v] - first[v] + 1);
    U32Ptr(pc.counts).v[t] = columns;
    atomicAdd(Total64(pc.total).v, uint64_t(columns));
}
