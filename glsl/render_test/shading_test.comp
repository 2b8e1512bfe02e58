#version 460
// Runs the shading library over a batch of cases so that tests can compare it with its CPU
// twin (renderer/src/shading/reference). Each case holds a material, a light and four vec4 of
// inputs; each result is 24 floats. The layout per mode is documented in tests/tests/shading.rs.
#include "common.glsl"
#include "render/rng.glsl"
#include "render/sampling.glsl"
#include "render/bsdf.glsl"
#include "render/solid_texture.glsl"
#include "render/lights.glsl"
#include "render/environment.glsl"

struct ShadingCase {
    Material m;
    Light l;
    vec4 a;
    vec4 b;
    vec4 c;
    vec4 d;
};

const uint RESULT_FLOATS = 24u;

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Cases { ShadingCase v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Results { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer EnvironmentRef { Environment e; };

layout(push_constant, scalar) uniform Push {
    uint64_t cases;
    uint64_t results;
    uint64_t environment;
    uint mode;
    uint n;
} pc;

float out_values[RESULT_FLOATS];

void put3(uint at, vec3 v) {
    out_values[at] = v.x;
    out_values[at + 1u] = v.y;
    out_values[at + 2u] = v.z;
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    for (uint k = 0u; k < RESULT_FLOATS; k++) {
        out_values[k] = 0.0;
    }
    ShadingCase c = Cases(pc.cases).v[i];
    if (pc.mode == SHADING_TEST_BSDF) {
        vec3 albedo = c.a.xyz;
        vec3 wo = c.b.xyz;
        put3(0u, bsdf_eval(c.m, albedo, wo, c.c.xyz));
        out_values[3] = bsdf_pdf(c.m, albedo, wo, c.c.xyz);
        BsdfSample s;
        bool ok = bsdf_sample(c.m, albedo, wo, c.d.xyz, s);
        out_values[4] = ok ? 1.0 : 0.0;
        put3(5u, s.wi);
        put3(8u, s.weight);
        out_values[11] = s.pdf;
        out_values[12] = s.specular ? 1.0 : 0.0;
        out_values[13] = bsdf_has_smooth_lobe(c.m) ? 1.0 : 0.0;
    } else if (pc.mode == SHADING_TEST_TEXTURE) {
        put3(0u, solid_texture_albedo(c.m, c.a.xyz));
    } else if (pc.mode == SHADING_TEST_LIGHT) {
        LightSample s;
        bool ok = light_sample(c.l, c.a.xyz, c.b.xy, s);
        out_values[0] = ok ? 1.0 : 0.0;
        put3(1u, s.wi);
        out_values[4] = s.dist;
        put3(5u, s.radiance);
        out_values[8] = s.pdf;
        float t;
        vec3 radiance;
        bool hit = light_intersect(c.l, c.c.xyz, c.d.xyz, c.c.w, t, radiance);
        out_values[9] = hit ? 1.0 : 0.0;
        out_values[10] = t;
        put3(11u, radiance);
        out_values[14] = hit ? light_pdf(c.l, c.c.xyz, c.d.xyz, t) : 0.0;
    } else if (pc.mode == SHADING_TEST_ENVIRONMENT) {
        Environment e = EnvironmentRef(pc.environment).e;
        put3(0u, env_eval(e, c.a.xyz));
        out_values[3] = env_pdf(e, c.a.xyz);
        vec3 dir;
        vec3 radiance;
        float pdf;
        bool ok = env_sample(e, c.b.xy, dir, radiance, pdf);
        out_values[4] = ok ? 1.0 : 0.0;
        put3(5u, dir);
        put3(8u, radiance);
        out_values[11] = pdf;
    } else if (pc.mode == SHADING_TEST_RNG) {
        uvec4 bits = floatBitsToUint(c.a);
        uint state = rng_init(bits.xy, bits.z, bits.w);
        for (uint k = 0u; k < 8u; k += 2u) {
            vec2 r = rng_next2(state);
            out_values[k] = r.x;
            out_values[k + 1u] = r.y;
        }
        put3(8u, sample_cosine_hemisphere(c.b.xy));
        put3(11u, sample_uniform_sphere(c.b.xy));
        vec2 disk = sample_concentric_disk(c.b.xy);
        out_values[14] = disk.x;
        out_values[15] = disk.y;
        vec3 t;
        vec3 b;
        make_frame(c.c.xyz, t, b);
        put3(16u, t);
        put3(19u, b);
        out_values[22] = pdf_cosine_hemisphere(c.b.z);
    }
    Results r = Results(pc.results);
    for (uint k = 0u; k < RESULT_FLOATS; k++) {
        r.v[i * RESULT_FLOATS + k] = out_values[k];
    }
}
