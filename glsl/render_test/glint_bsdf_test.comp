#version 460
// Runs the glint material (render/glint_bsdf.glsl) on test cases so that tests can compare it
// with its CPU twin (renderer/src/shading/reference/glint.rs). Each case is 33 floats: the
// object-space point (3), instance scale, cone width, world shading normal (3), world wo (3),
// object x and z axes in world (3 + 3), local wo (3), local wi (3), random numbers (3),
// conductor eta (3) and kappa (3), and the index of its record. Each result is 24 floats:
// footprint centre (2), sigma_P, frame t (3) and b (3), glint_eval (3), glint_pdf, sample ok,
// sampled wi (3), weight (3), pdf, and 3 unused.
#include "common.glsl"
#include "render/glint_bsdf.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer GlintBsdfRecords { GlintRecord v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer GlintBsdfCases { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer GlintBsdfResults { float v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t records;
    uint64_t cases;
    uint64_t results;
    uint n;
} pc;

const uint CASE_FLOATS = 33u;
const uint RESULT_FLOATS = 24u;

GlintBsdfCases cs;
uint at;

vec3 next3() {
    vec3 v = vec3(cs.v[at], cs.v[at + 1u], cs.v[at + 2u]);
    at += 3u;
    return v;
}

float next1() {
    float v = cs.v[at];
    at += 1u;
    return v;
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    cs = GlintBsdfCases(pc.cases);
    at = i * CASE_FLOATS;
    vec3 p = next3();
    float scale = next1();
    float footprint = next1();
    vec3 ns = next3();
    vec3 wo_world = next3();
    vec3 ex = next3();
    vec3 ez = next3();
    vec3 wo = next3();
    vec3 wi = next3();
    vec3 u = next3();
    Material m;
    m.color = next3();
    m.k = next3();
    GlintRecord g = GlintBsdfRecords(pc.records).v[uint(next1())];

    vec3 t_axis, b_axis;
    GlintShade gs = glint_shade(g, p, scale, footprint, ns, wo_world, ex, ez, vec2(0.0), ex, vec2(0.0), vec2(0.0), t_axis, b_axis);
    vec3 f = glint_eval(g, m, gs, wo, wi);
    float pdf = glint_pdf(g, gs, wo, wi);
    BsdfSample s;
    bool ok = glint_sample(g, m, gs, wo, u, s);

    float o[RESULT_FLOATS] = float[RESULT_FLOATS](
        gs.u.x, gs.u.y, gs.sigma_p, t_axis.x, t_axis.y, t_axis.z, b_axis.x, b_axis.y, b_axis.z,
        f.x, f.y, f.z, pdf, ok ? 1.0 : 0.0, s.wi.x, s.wi.y, s.wi.z, s.weight.x, s.weight.y,
        s.weight.z, s.pdf, 0.0, 0.0, 0.0);
    GlintBsdfResults r = GlintBsdfResults(pc.results);
    for (uint k = 0u; k < RESULT_FLOATS; k++) {
        r.v[i * RESULT_FLOATS + k] = o[k];
    }
}
