// Procedural solid textures evaluated at rest-pose object-space points. Marble is the stores'
// integer marble (store/marble.glsl, exact on every device). Wood's noise is gradient noise
// whose lattice gradients come from an integer hash of the cell coordinates, so that the CPU
// twin (renderer/src/shading/reference/texture.rs) reproduces it to float rounding.
#ifndef LAZYSOLID_RENDER_SOLID_TEXTURE_GLSL
#define LAZYSOLID_RENDER_SOLID_TEXTURE_GLSL

#include "render/math.glsl"
#include "render/material.glsl"
#include "store/marble.glsl"

// Octaves of the wood perturbation.
const int TEXTURE_WOOD_OCTAVES = 3;
// Noise seed of the marble texture.
const uint TEXTURE_MARBLE_SEED = 0u;

// A 32-bit integer mixer (xor-shift-multiply, constants from Wellons' hash-prospector search).
uint texture_hash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// Gradient of lattice point c: three 10-bit fields of its hash mapped to [-1, 1].
vec3 texture_gradient(ivec3 c) {
    uint h = texture_hash(uint(c.x) ^ texture_hash(uint(c.y) ^ texture_hash(uint(c.z))));
    vec3 g = vec3(float(h & 1023u), float((h >> 10u) & 1023u), float((h >> 20u) & 1023u));
    return g * (2.0 / 1023.0) - 1.0;
}

// Gradient noise with quintic interpolation; roughly in [-1, 1], 0 on lattice points.
float texture_noise(vec3 p) {
    vec3 fl = floor(p);
    ivec3 c = ivec3(fl);
    vec3 r = p - fl;
    vec3 w = r * r * r * (r * (r * 6.0 - 15.0) + 10.0);
    float n000 = dot(texture_gradient(c), r);
    float n100 = dot(texture_gradient(c + ivec3(1, 0, 0)), r - vec3(1.0, 0.0, 0.0));
    float n010 = dot(texture_gradient(c + ivec3(0, 1, 0)), r - vec3(0.0, 1.0, 0.0));
    float n110 = dot(texture_gradient(c + ivec3(1, 1, 0)), r - vec3(1.0, 1.0, 0.0));
    float n001 = dot(texture_gradient(c + ivec3(0, 0, 1)), r - vec3(0.0, 0.0, 1.0));
    float n101 = dot(texture_gradient(c + ivec3(1, 0, 1)), r - vec3(1.0, 0.0, 1.0));
    float n011 = dot(texture_gradient(c + ivec3(0, 1, 1)), r - vec3(0.0, 1.0, 1.0));
    float n111 = dot(texture_gradient(c + ivec3(1, 1, 1)), r - vec3(1.0, 1.0, 1.0));
    float x00 = n000 + w.x * (n100 - n000);
    float x10 = n010 + w.x * (n110 - n010);
    float x01 = n001 + w.x * (n101 - n001);
    float x11 = n011 + w.x * (n111 - n011);
    float y0 = x00 + w.y * (x10 - x00);
    float y1 = x01 + w.y * (x11 - x01);
    return y0 + w.z * (y1 - y0);
}

// Sum of octaves of noise (smooth fbm).
float texture_fractal(vec3 p, int octaves) {
    float sum = 0.0;
    float amplitude = 1.0;
    for (int o = 0; o < octaves; o++) {
        float n = texture_noise(p);
        sum += amplitude * n;
        p *= 2.0;
        amplitude *= 0.5;
    }
    return sum;
}

// Blend weight of colour b at p (scaled to features): marble veins (colour b), wood rings or
// checks.
float solid_texture_blend(uint kind, vec3 p) {
    if (texture_kind_used(TEXTURE_MARBLE) && kind == TEXTURE_MARBLE) {
        return 1.0 - float(marble_band_at(p, TEXTURE_MARBLE_SEED)) / float(MARBLE_BAND_ONE);
    }
    if (texture_kind_used(TEXTURE_WOOD) && kind == TEXTURE_WOOD) {
        float r = sqrt(p.x * p.x + p.z * p.z) + 0.5 * texture_fractal(p, TEXTURE_WOOD_OCTAVES);
        float ring = 0.5 + 0.5 * cos(TWO_PI * r);
        return ring * ring * (3.0 - 2.0 * ring);
    }
    ivec3 c = ivec3(floor(p));
    return ((c.x + c.y + c.z) & 1) == 0 ? 0.0 : 1.0;
}

// Albedo of material m at rest-pose object-space point p_object (m.color without texture).
vec3 solid_texture_albedo(Material m, vec3 p_object) {
    if (m.texture_kind == TEXTURE_NONE) {
        return m.color;
    }
    float t = solid_texture_blend(m.texture_kind, p_object * m.tex_scale);
    return m.tex_color_a * (1.0 - t) + m.tex_color_b * t;
}

#endif
