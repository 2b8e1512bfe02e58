// Constants and frame helpers shared by the shading library (renderer/src/shading/reference
// holds the CPU twin of every function here and in the other render/*.glsl files).
#ifndef LAZYSOLID_RENDER_MATH_GLSL
#define LAZYSOLID_RENDER_MATH_GLSL

const float PI = 3.14159265358979;
const float TWO_PI = 6.28318530717959;
const float INV_PI = 0.318309886183791;

// Orthonormal basis (t, b, n) around the unit vector n, right-handed (t x b = n), without a
// singularity: the branchless construction of Duff et al. 2017 ("Building an Orthonormal Basis,
// Revisited"), with the sign taken as +1 at n.z = 0.
void make_frame(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// n kept at least slightly facing the viewer v when the unbent normal ns faces it: a view
// below the shading hemisphere would shade black. Normal maps, relief and vMF lobes all go
// through it, so every filter of a map sees the same surface.
vec3 facing_normal(vec3 ns, vec3 n, vec3 v) {
    float facing = dot(n, v);
    if (dot(ns, v) > 0.0 && facing < 0.05) {
        n = normalize(n + (0.05 - facing) * v);
    }
    return n;
}

// World direction v in the local shading frame (t, b, n): z along n.
vec3 to_local(vec3 v, vec3 t, vec3 b, vec3 n) {
    return vec3(dot(v, t), dot(v, b), dot(v, n));
}

// Local direction v back in world space.
vec3 from_local(vec3 v, vec3 t, vec3 b, vec3 n) {
    return v.x * t + v.y * b + v.z * n;
}

#endif
