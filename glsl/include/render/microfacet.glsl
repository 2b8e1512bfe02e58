// Isotropic GGX (Trowbridge-Reitz) microfacet distribution in the local frame (z = normal),
// with the height-correlated Smith masking-shadowing G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) and
// visible-normal sampling (Heitz 2018, "Sampling the GGX Distribution of Visible Normals").
// CPU twin: renderer/src/shading/reference/microfacet.rs.
#ifndef LAZYSOLID_RENDER_MICROFACET_GLSL
#define LAZYSOLID_RENDER_MICROFACET_GLSL

#include "render/math.glsl"

// Below this alpha a lobe is treated as perfectly smooth (a delta): the GGX lobe is then
// narrower than float precision can sample and evaluate consistently.
const float GGX_MIN_ALPHA = 1e-3;

// Normal distribution D(m) for a unit m; the denominator is written as
// (m.x^2 + m.y^2) + alpha^2 m.z^2 so that it does not cancel near the normal.
float ggx_d(vec3 m, float alpha) {
    if (m.z <= 0.0) {
        return 0.0;
    }
    float a2 = alpha * alpha;
    float t = m.x * m.x + m.y * m.y + a2 * m.z * m.z;
    return a2 / (PI * t * t);
}

// Smith Lambda(w) = (sqrt(1 + alpha^2 tan^2) - 1) / 2, written without cancellation.
float ggx_lambda(vec3 w, float alpha) {
    float z2 = w.z * w.z;
    float t2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
    return 0.5 * t2 / (1.0 + sqrt(1.0 + t2));
}

// Masking of one direction.
float ggx_g1(vec3 w, float alpha) {
    return 1.0 / (1.0 + ggx_lambda(w, alpha));
}

// Height-correlated masking-shadowing of a pair.
float ggx_g2(vec3 wo, vec3 wi, float alpha) {
    return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// A microfacet normal distributed as the normals visible from wo (wo.z > 0): density
// D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z.
vec3 ggx_sample_vndf(vec3 wo, float alpha, vec2 u) {
    vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) / sqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x);
    float phi = TWO_PI * u.y;
    float p1 = r * cos(phi);
    float p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0, nh.z)));
}

// Density of ggx_sample_vndf producing m.
float ggx_vndf_pdf(vec3 wo, vec3 m, float alpha) {
    return ggx_g1(wo, alpha) * max(0.0, dot(wo, m)) * ggx_d(m, alpha) / wo.z;
}

#endif
