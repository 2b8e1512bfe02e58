// Exact triangle–box overlap by the separating axis theorem, operation for operation the same
// as compute/src/voxel/triangle_box.rs: every value is `precise` (no fused multiply-adds) and
// dot and cross products are summed in glam's order, so the GPU and CPU voxelizers agree bit
// for bit.
#ifndef LAZYSOLID_VOXEL_TRIANGLE_BOX_GLSL
#define LAZYSOLID_VOXEL_TRIANGLE_BOX_GLSL

float tb_dot(vec3 a, vec3 b) {
    precise float xy = a.x * b.x + a.y * b.y;
    precise float r = xy + a.z * b.z;
    return r;
}

vec3 tb_cross(vec3 a, vec3 b) {
    precise vec3 r = vec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
    return r;
}

// Whether the triangle (t0, t1, t2) overlaps the box of `center` and `half` extent; touching
// counts as overlapping.
bool triangle_box_overlap(vec3 center, vec3 half_size, vec3 t0, vec3 t1, vec3 t2) {
    precise vec3 v0 = t0 - center;
    precise vec3 v1 = t1 - center;
    precise vec3 v2 = t2 - center;
    for (int a = 0; a < 3; ++a) {
        float lo = min(min(v0[a], v1[a]), v2[a]);
        float hi = max(max(v0[a], v1[a]), v2[a]);
        if (lo > half_size[a] || hi < -half_size[a]) {
            return false;
        }
    }
    precise vec3 e[3] = vec3[3](v1 - v0, v2 - v1, v0 - v2);
    vec3 n = tb_cross(e[0], e[1]);
    float r = tb_dot(half_size, abs(n));
    float d = tb_dot(n, v0);
    if (d > r || d < -r) {
        return false;
    }
    for (int i = 0; i < 3; ++i) {
        for (int a = 0; a < 3; ++a) {
            vec3 unit = vec3(0.0);
            unit[a] = 1.0;
            vec3 axis = tb_cross(unit, e[i]);
            if (axis == vec3(0.0)) {
                continue;
            }
            float p0 = tb_dot(axis, v0);
            float p1 = tb_dot(axis, v1);
            float p2 = tb_dot(axis, v2);
            float plo = min(min(p0, p1), p2);
            float phi = max(max(p0, p1), p2);
            float ra = tb_dot(half_size, abs(axis));
            if (plo > ra || phi < -ra) {
                return false;
            }
        }
    }
    return true;
}

#endif
