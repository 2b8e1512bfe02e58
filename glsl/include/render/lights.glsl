// Analytic area lights: spheres (sampled over the cone of directions they subtend) and
// parallelograms (sampled by area, converted to solid angle). Must match
// renderer/src/shading/light.rs (GpuLight, 64 bytes); CPU twin:
// renderer/src/shading/reference/lights.rs.
#ifndef LAZYSOLID_RENDER_LIGHTS_GLSL
#define LAZYSOLID_RENDER_LIGHTS_GLSL

#include "render/math.glsl"

struct Light {
    vec3 p;          // sphere centre, or quad corner
    uint kind;       // LIGHT_*
    vec3 u;          // quad first edge
    float radius;    // sphere radius
    vec3 v;          // quad second edge; a one-sided quad emits towards u x v
    uint two_sided;  // quad emits on both faces when non-zero
    vec3 radiance;   // emitted radiance
    float area;      // surface area (|u x v| for a quad)
};

struct LightSample {
    vec3 wi;         // unit direction from x towards the light
    float dist;      // distance from x to the sampled point
    vec3 radiance;   // radiance arriving from it
    float pdf;       // solid-angle pdf at x
};

// 1 - cos(theta_max) of the cone a sphere of squared radius r2 subtends at squared distance d2
// (> r2), written without cancellation for distant spheres.
float light_sphere_cone(float r2, float d2) {
    float s2 = r2 / d2;
    return s2 / (1.0 + sqrt(max(0.0, 1.0 - s2)));
}

// A direction from x towards light l and what arrives along it; false when l cannot be sampled
// from x (inside a sphere, behind a one-sided quad, on the light).
bool light_sample(Light l, vec3 x, vec2 u, out LightSample s) {
    s = LightSample(vec3(0.0), 0.0, vec3(0.0), 0.0);
    if (l.kind == LIGHT_SPHERE) {
        vec3 to_c = l.p - x;
        float d2 = dot(to_c, to_c);
        float r2 = l.radius * l.radius;
        if (d2 <= r2) {
            return false;
        }
        float d = sqrt(d2);
        vec3 w = to_c / d;
        float cone = light_sphere_cone(r2, d2);
        float omc = u.x * cone;
        float cos_t = 1.0 - omc;
        float sin2_t = omc * (2.0 - omc);
        float sin_t = sqrt(max(0.0, sin2_t));
        float phi = TWO_PI * u.y;
        vec3 t;
        vec3 b;
        make_frame(w, t, b);
        s.wi = normalize((sin_t * cos(phi)) * t + (sin_t * sin(phi)) * b + cos_t * w);
        s.dist = d * cos_t - sqrt(max(0.0, r2 - d2 * sin2_t));
        s.radiance = l.radiance;
        s.pdf = 1.0 / (TWO_PI * cone);
        return s.dist > 0.0;
    }
    vec3 to_y = l.p + u.x * l.u + u.y * l.v - x;
    float dist2 = dot(to_y, to_y);
    if (dist2 <= 0.0) {
        return false;
    }
    s.dist = sqrt(dist2);
    s.wi = to_y / s.dist;
    vec3 n = cross(l.u, l.v) / l.area;
    float cos_l = -dot(s.wi, n);
    if (l.two_sided != 0u) {
        cos_l = abs(cos_l);
    }
    if (cos_l <= 0.0) {
        return false;
    }
    s.radiance = l.radiance;
    s.pdf = dist2 / (cos_l * l.area);
    return true;
}

// Solid-angle pdf with which light_sample from x produces the direction wi that hits l at dist
// (as light_intersect reported it).
float light_pdf(Light l, vec3 x, vec3 wi, float dist) {
    if (l.kind == LIGHT_SPHERE) {
        vec3 to_c = l.p - x;
        float d2 = dot(to_c, to_c);
        float r2 = l.radius * l.radius;
        return d2 <= r2 ? 0.0 : 1.0 / (TWO_PI * light_sphere_cone(r2, d2));
    }
    vec3 n = cross(l.u, l.v) / l.area;
    float cos_l = -dot(wi, n);
    if (l.two_sided != 0u) {
        cos_l = abs(cos_l);
    }
    return cos_l <= 0.0 ? 0.0 : dist * dist / (cos_l * l.area);
}

// First hit of the ray o + t d (d unit) with l for t in (0, tmax), and the radiance it sees
// there (0 on the back of a one-sided quad, which still occludes).
bool light_intersect(Light l, vec3 o, vec3 d, float tmax, out float t, out vec3 radiance) {
    t = 0.0;
    radiance = vec3(0.0);
    if (l.kind == LIGHT_SPHERE) {
        vec3 f = o - l.p;
        float b = dot(f, d);
        vec3 perp = f - b * d;
        float disc = l.radius * l.radius - dot(perp, perp);
        if (disc < 0.0) {
            return false;
        }
        float q = sqrt(disc);
        float t0 = -b - q;
        float hit = t0 > 0.0 ? t0 : -b + q;
        if (hit <= 0.0 || hit >= tmax) {
            return false;
        }
        t = hit;
        radiance = l.radiance;
        return true;
    }
    vec3 nrm = cross(l.u, l.v);
    float denom = dot(nrm, d);
    if (denom == 0.0) {
        return false;
    }
    float hit = dot(l.p - o, nrm) / denom;
    if (hit <= 0.0 || hit >= tmax) {
        return false;
    }
    vec3 q = o + hit * d - l.p;
    vec3 w = nrm / dot(nrm, nrm);
    float a = dot(w, cross(q, l.v));
    float c = dot(w, cross(l.u, q));
    if (a < 0.0 || a > 1.0 || c < 0.0 || c > 1.0) {
        return false;
    }
    t = hit;
    radiance = (l.two_sided != 0u || denom < 0.0) ? l.radiance : vec3(0.0);
    return true;
}

#endif
