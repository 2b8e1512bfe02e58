#version 460
// Voxelization, steps 2 and 3: one invocation per column (of any triangle) tests the few cells
// of the column that the triangle's plane can reach with the exact triangle–box overlap.
// write == 0: counts[c] = the overlapping cells, total += counts[c].
// write == 1: counts holds the scanned offsets; the cells' Morton keys go to keys[counts[c]..].
// The column range along the dominant axis w is the plane's extent over the column, widened by
// one cell each side (the overlap test decides; the margin only absorbs rounding), so a column
// never holds more than 7 candidates whatever the triangle's size.
#extension GL_EXT_shader_atomic_int64 : require
#include "common.glsl"
#include "morton.glsl"
#include "voxel/grid.glsl"
#include "voxel/triangle_box.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t positions;
    uint64_t triangles;
    uint64_t column_offsets;
    uint64_t counts;
    uint64_t keys;
    uint64_t total;
    uint n_triangles;
    uint n_columns;
    uint extent;
    float r;
    float shift;
    float center_offset;
    float half_size;
    uint write;
} pc;

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Total64 { uint64_t v; };

void main() {
    uint c = uint(global_index());
    if (c >= pc.n_columns) {
        return;
    }
    // The triangle owning column c: the last t with column_offsets[t] <= c.
    U32Ptr offsets = U32Ptr(pc.column_offsets);
    uint lo = 0u;
    uint hi = pc.n_triangles;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (offsets.v[mid] <= c) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    uint t = lo;
    Triangle tri = load_triangle(pc.positions, pc.triangles, t);
    ivec3 first, last;
    cell_range(tri, pc.r, pc.shift, pc.extent, first, last);
    int w = dominant_axis(tri);
    int u = (w + 1) % 3;
    int v = (w + 2) % 3;
    uint local = c - offsets.v[t];
    uint width = uint(last[u] - first[u] + 1);
    ivec3 cell = ivec3(0);
    cell[u] = first[u] + int(local % width);
    cell[v] = first[v] + int(local / width);

    int w_first = first[w];
    int w_last = last[w];
    vec3 n = cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[1]);
    if (n[w] != 0.0) {
        // The plane's w over the column's four corners, in grid coordinates.
        float gmin = 1e30;
        float gmax = -1e30;
        for (int k = 0; k < 4; ++k) {
            float pu = (float(cell[u] + (k & 1)) - pc.shift) / pc.r;
            float pv = (float(cell[v] + (k >> 1)) - pc.shift) / pc.r;
            float pw = tri.p[0][w] - (n[u] * (pu - tri.p[0][u]) + n[v] * (pv - tri.p[0][v])) / n[w];
            float g = pw * pc.r + pc.shift;
            gmin = min(gmin, g);
            gmax = max(gmax, g);
        }
        gmin = clamp(gmin, -4.0, float(pc.extent) + 4.0);
        gmax = clamp(gmax, -4.0, float(pc.extent) + 4.0);
        w_first = max(w_first, int(floor(gmin)) - 2);
        w_last = min(w_last, int(floor(gmax)) + 1);
    }

    vec3 half_size = vec3(pc.half_size);
    uint count = 0u;
    uint base = pc.write != 0u ? U32Ptr(pc.counts).v[c] : 0u;
    for (int k = w_first; k <= w_last; ++k) {
        cell[w] = k;
        precise vec3 center = (vec3(cell) + pc.center_offset) / pc.r;
        if (triangle_box_overlap(center, half_size, tri.p[0], tri.p[1], tri.p[2])) {
            if (pc.write != 0u) {
                U64Ptr(pc.keys).v[base + count] = morton3(uvec3(cell));
            }
            count += 1u;
        }
    }
    if (pc.write == 0u) {
        U32Ptr(pc.counts).v[c] = count;
        atomicAdd(Total64(pc.total).v, uint64_t(count));
    }
}
