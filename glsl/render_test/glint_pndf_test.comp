#version 460
// Runs the glint P-NDF (glint/pndf.glsl) on test cases so that tests can compare it with its
// CPU twin (renderer/src/glint/pndf.rs). Each case is 12 floats: footprint centre (2), sigma_P,
// s (2), shading point u (2), random numbers (3), the footprint's stretch (2). Each result is 6 floats: pruned D_P,
// unpruned (explicit) D_P, texels the pruned sum evaluated, the s sampled at u (2) and its
// sampling density.
#include "common.glsl"
#include "glint/pndf.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer PndfCases { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer PndfResults { float v[]; };

layout(push_constant, scalar) uniform Push {
    GlintMap map;
    uint64_t ranges;
    uint64_t cases;
    uint64_t results;
    float sigma_r;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    PndfCases c = PndfCases(pc.cases);
    uint at = i * 12u;
    vec2 center = vec2(c.v[at], c.v[at + 1u]);
    float sigma_p = c.v[at + 2u];
    vec2 s = vec2(c.v[at + 3u], c.v[at + 4u]);
    vec2 u = vec2(c.v[at + 5u], c.v[at + 6u]);
    vec3 rnd = vec3(c.v[at + 7u], c.v[at + 8u], c.v[at + 9u]);
    vec2 stretch = vec2(c.v[at + 10u], c.v[at + 11u]);
    uint texels;
    uint all_texels;
    float pruned = glint_pndf(pc.map, pc.ranges, center, sigma_p, stretch, s, pc.sigma_r, true, texels);
    float explicit_ = glint_pndf(pc.map, pc.ranges, center, sigma_p, stretch, s, pc.sigma_r, false, all_texels);
    GlintSampleTexels t = glint_sample_texels(pc.map, u, pc.sigma_r);
    vec2 drawn = glint_sample_s(t, rnd);
    PndfResults r = PndfResults(pc.results);
    uint o = i * 6u;
    r.v[o] = pruned;
    r.v[o + 1u] = explicit_;
    r.v[o + 2u] = float(texels);
    r.v[o + 3u] = drawn.x;
    r.v[o + 4u] = drawn.y;
    r.v[o + 5u] = glint_sample_pdf(t, drawn);
}
