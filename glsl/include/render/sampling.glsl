// Warps from the unit square to directions and discs. CPU twin:
// renderer/src/shading/reference/sampling.rs.
#ifndef LAZYSOLID_RENDER_SAMPLING_GLSL
#define LAZYSOLID_RENDER_SAMPLING_GLSL

#include "render/math.glsl"

// Shirley and Chiu's concentric map of [0,1)^2 onto the unit disc, in polar form: signed
// radius r, 1 - |r| computed exactly from u (no cancellation near the rim), and angle theta.
void concentric_polar(vec2 u, out float r, out float one_minus_r, out float theta) {
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0) {
        r = 0.0;
        one_minus_r = 1.0;
        theta = 0.0;
    } else if (abs(o.x) > abs(o.y)) {
        r = o.x;
        one_minus_r = 2.0 * min(u.x, 1.0 - u.x);
        theta = (0.25 * PI) * (o.y / o.x);
    } else {
        r = o.y;
        one_minus_r = 2.0 * min(u.y, 1.0 - u.y);
        theta = 0.5 * PI - (0.25 * PI) * (o.x / o.y);
    }
}

// The concentric map: low distortion, so stratified samples stay stratified.
vec2 sample_concentric_disk(vec2 u) {
    float r;
    float one_minus_r;
    float theta;
    concentric_polar(u, r, one_minus_r, theta);
    return r * vec2(cos(theta), sin(theta));
}

// Cosine-weighted direction around +z (Malley's method on the concentric disc); z is
// sqrt((1 - r)(1 + r)), accurate for directions near the horizon.
vec3 sample_cosine_hemisphere(vec2 u) {
    float r;
    float one_minus_r;
    float theta;
    concentric_polar(u, r, one_minus_r, theta);
    return vec3(r * cos(theta), r * sin(theta), sqrt(one_minus_r * (2.0 - one_minus_r)));
}

// Solid-angle density of sample_cosine_hemisphere (0 below the horizon).
float pdf_cosine_hemisphere(float cos_theta) {
    return max(cos_theta, 0.0) * INV_PI;
}

// Uniform direction on the unit sphere: density 1 / (4 pi).
vec3 sample_uniform_sphere(vec2 u) {
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = TWO_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

#endif
