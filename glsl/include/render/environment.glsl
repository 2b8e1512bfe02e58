// Radiance from infinity: a constant, or a lat-long HDR map importance-sampled through a
// piecewise-constant 2D distribution of luminance x sin(theta). Must match
// renderer/src/shading/gpu_environment.rs (EnvironmentParams, 72 bytes); CPU twin:
// renderer/src/shading/reference/environment.rs.
//
// Lat-long convention: +y is up; image column u in [0, 1) turns from -z (u = 0) towards +x
// (u = 1/4); row v in [0, 1) runs from +y (v = 0) down to -y. The map is rotated about +y by
// the rotation angle: world = R_y(angle) map, R_y taking +z towards +x.
#ifndef LAZYSOLID_RENDER_ENVIRONMENT_GLSL
#define LAZYSOLID_RENDER_ENVIRONMENT_GLSL

#include "common.glsl"
#include "render/math.glsl"
#include "render/sampling.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EnvF32 { float v[]; };

struct Environment {
    vec3 radiance;            // constant radiance (ENVIRONMENT_CONSTANT)
    uint kind;                // ENVIRONMENT_*
    float intensity;          // multiplier of the map's texels
    float rotation_cos;       // cos and sin of the rotation about +y
    float rotation_sin;
    uint width;               // map size in texels
    uint height;
    uint sampleable;          // 0 when nothing can be sampled (black map or constant)
    uint64_t texels;          // width * height RGB floats, row 0 at the top (+y)
    uint64_t pdf;             // width * height floats: density over the unit square of (u, v)
    uint64_t marginal_cdf;    // height + 1 floats, 0 first and 1 last
    uint64_t conditional_cdf; // height rows of width + 1 floats
};

// Largest i in [0, count - 2] with cdf[offset + i] <= u, for cdf[offset] <= u < cdf[last].
uint env_find_interval(EnvF32 cdf, uint offset, uint count, float u) {
    uint lo = 0u;
    uint hi = count - 1u;
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (cdf.v[offset + mid] <= u) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// World direction of map direction m.
vec3 env_to_world(Environment e, vec3 m) {
    return vec3(e.rotation_cos * m.x + e.rotation_sin * m.z, m.y,
                -e.rotation_sin * m.x + e.rotation_cos * m.z);
}

// Map direction of world direction w.
vec3 env_to_map(Environment e, vec3 w) {
    return vec3(e.rotation_cos * w.x - e.rotation_sin * w.z, w.y,
                e.rotation_sin * w.x + e.rotation_cos * w.z);
}

// Texel (column, row) of unit world direction dir, and sin(theta) there.
uvec2 env_texel(Environment e, vec3 dir, out float sin_theta) {
    vec3 m = env_to_map(e, dir);
    sin_theta = sqrt(m.x * m.x + m.z * m.z);
    float phi = atan(m.x, -m.z);
    if (phi < 0.0) {
        phi += TWO_PI;
    }
    float theta = acos(clamp(m.y, -1.0, 1.0));
    uint col = min(uint(phi * (1.0 / TWO_PI) * float(e.width)), e.width - 1u);
    uint row = min(uint(theta * INV_PI * float(e.height)), e.height - 1u);
    return uvec2(col, row);
}

// Radiance of texel (col, row), intensity included.
vec3 env_texel_radiance(Environment e, uvec2 texel) {
    EnvF32 t = EnvF32(e.texels);
    uint i = 3u * (texel.y * e.width + texel.x);
    return e.intensity * vec3(t.v[i], t.v[i + 1u], t.v[i + 2u]);
}

// Radiance arriving from unit world direction dir (nearest texel).
vec3 env_eval(Environment e, vec3 dir) {
    if (e.kind == ENVIRONMENT_CONSTANT) {
        return e.radiance;
    }
    float sin_theta;
    return env_texel_radiance(e, env_texel(e, dir, sin_theta));
}

// Solid-angle density with which env_sample produces unit direction dir.
float env_pdf(Environment e, vec3 dir) {
    if (e.sampleable == 0u) {
        return 0.0;
    }
    if (e.kind == ENVIRONMENT_CONSTANT) {
        return 0.25 * INV_PI;
    }
    float sin_theta;
    uvec2 texel = env_texel(e, dir, sin_theta);
    if (sin_theta <= 0.0) {
        return 0.0;
    }
    float p = EnvF32(e.pdf).v[texel.y * e.width + texel.x];
    return p / (2.0 * PI * PI * sin_theta);
}

// A direction drawn proportionally to luminance (uniformly for a constant), the radiance from
// it and its solid-angle pdf; false when there is nothing to sample.
bool env_sample(Environment e, vec2 u, out vec3 dir, out vec3 radiance, out float pdf) {
    dir = vec3(0.0, 1.0, 0.0);
    radiance = vec3(0.0);
    pdf = 0.0;
    if (e.sampleable == 0u) {
        return false;
    }
    if (e.kind == ENVIRONMENT_CONSTANT) {
        dir = sample_uniform_sphere(u);
        radiance = e.radiance;
        pdf = 0.25 * INV_PI;
        return true;
    }
    EnvF32 marginal = EnvF32(e.marginal_cdf);
    EnvF32 conditional = EnvF32(e.conditional_cdf);
    uint row = env_find_interval(marginal, 0u, e.height + 1u, u.y);
    float m0 = marginal.v[row];
    float dv = (u.y - m0) / (marginal.v[row + 1u] - m0);
    uint offset = row * (e.width + 1u);
    uint col = env_find_interval(conditional, offset, e.width + 1u, u.x);
    float c0 = conditional.v[offset + col];
    float du = (u.x - c0) / (conditional.v[offset + col + 1u] - c0);
    float theta = (float(row) + dv) / float(e.height) * PI;
    float phi = (float(col) + du) / float(e.width) * TWO_PI;
    float sin_theta = sin(theta);
    if (sin_theta <= 0.0) {
        return false;
    }
    dir = env_to_world(e, vec3(sin_theta * sin(phi), cos(theta), -sin_theta * cos(phi)));
    radiance = env_texel_radiance(e, uvec2(col, row));
    pdf = EnvF32(e.pdf).v[row * e.width + col] / (2.0 * PI * PI * sin_theta);
    return pdf > 0.0;
}

#endif
