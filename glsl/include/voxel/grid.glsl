// The triangles of a mesh (through device addresses) and the cell ranges they can touch on a
// voxel grid (see compute/src/voxel/grid.rs): cell i spans [i, i + 1] in grid coordinates
// g = v * R + shift, and its centre is (i + center_offset) / R.
#ifndef LAZYSOLID_VOXEL_GRID_GLSL
#define LAZYSOLID_VOXEL_GRID_GLSL

#include "common.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer F32Ptr { float v[]; };

struct Triangle {
    vec3 p[3];
};

Triangle load_triangle(uint64_t positions, uint64_t triangles, uint t) {
    U32Ptr idx = U32Ptr(triangles);
    F32Ptr pos = F32Ptr(positions);
    Triangle tri;
    for (uint k = 0u; k < 3u; ++k) {
        uint v = idx.v[3u * t + k];
        tri.p[k] = vec3(pos.v[3u * v], pos.v[3u * v + 1u], pos.v[3u * v + 2u]);
    }
    return tri;
}

// First and last cells (inclusive) whose closed box can touch the triangle's bounding box,
// exactly as grid_cells_cpu computes them.
void cell_range(Triangle tri, float r, float shift, uint extent, out ivec3 first, out ivec3 last) {
    vec3 lo = min(min(tri.p[0], tri.p[1]), tri.p[2]);
    vec3 hi = max(max(tri.p[0], tri.p[1]), tri.p[2]);
    precise vec3 glo = lo * r + shift;
    precise vec3 ghi = hi * r + shift;
    first = clamp(ivec3(ceil(glo)) - 1, ivec3(0), ivec3(int(extent) - 1));
    last = clamp(ivec3(floor(ghi)), ivec3(0), ivec3(int(extent) - 1));
}

// The axis along which the triangle's normal is largest: the triangle is walked in columns
// along it, each column holding at most a few candidate cells.
int dominant_axis(Triangle tri) {
    // precise: the column count and the column walk must pick the same axis in both kernels.
    precise vec3 e0 = tri.p[1] - tri.p[0];
    precise vec3 e1 = tri.p[2] - tri.p[1];
    precise vec3 n = abs(vec3(e0.y * e1.z - e1.y * e0.z, e0.z * e1.x - e1.z * e0.x, e0.x * e1.y - e1.x * e0.y));
    if (n.x >= n.y && n.x >= n.z) {
        return 0;
    }
    return n.y >= n.z ? 1 : 2;
}

#endif
