// The glint material: a conductor (Fresnel of eta, kappa) whose NDF is the P-NDF of a
// microstructure by example over the ray's footprint (glint/pndf.glsl), with a Smith GGX
// shadowing term of the example's RMS slope. In the glint frame (x, y: the surface
// coordinates' directions, z: the shading normal), with s = (h_x, h_y):
//   f cos_i = F(wo.h) G2(wo, wi) D_P(s) / (4 wo.z)
// D_P is a density of s, which is the projected-area measure of h, so it needs no cosine.
// Sampling draws s from the 4 texels around the footprint centre (glint_sample_s) and reflects;
// its solid-angle density is p_s(s) h.z / (4 wo.h), the density MIS weights use.
// Host side: renderer/src/glint/gpu_material.rs; CPU twins of the P-NDF and sampling:
// renderer/src/glint/pndf.rs, of this file: renderer/src/shading/reference/glint.rs (tested
// input by input through glsl/render_test/glint_bsdf_test.comp in tests/tests/glint_bsdf.rs).
#ifndef LAZYSOLID_RENDER_GLINT_BSDF_GLSL
#define LAZYSOLID_RENDER_GLINT_BSDF_GLSL

#include "glint/pndf.glsl"
#include "render/bsdf.glsl"

struct GlintRecord {
    GlintMap map;
    uint64_t ranges;        // the example's range table
    uint levels;            // its levels
    float sigma_r;          // intrinsic roughness
    float texels_per_unit;  // example texels per scene unit
    uint projection;        // GLINT_UV_*
    uint prune;             // 0: every texel of the footprint (the explicit reference)
    float shadow_alpha;     // GGX alpha of the shadowing term
    float max_footprint;    // largest sigma_P in texels
};

// Where a ray meets a glint surface: footprint centre u (texels), width sigma_p (texels) and
// stretch (texels; covariance sigma_p^2 I + stretch stretch^T, zero for the projections' pixel
// cone).
struct GlintShade {
    vec2 u;
    float sigma_p;
    vec2 stretch;
};

// The footprint and glint frame at a hit. `p` is the object-space hit point, `scale` the
// instance's scale, `footprint` the ray cone's width at the hit (scene units), `ns` the world
// shading normal, `wo_world` the direction back along the ray, `dpdu_world_x` and
// `dpdu_world_z` the object x and z axes in world (unit length).
// With GLINT_UV_MESH, `mesh_uv` and `mesh_dpdu` are the mesh's texture coordinates and the
// world direction of growing u, and `fp_a`, `fp_b` the footprint's two axes in texture
// coordinates (from ray differentials, so already foreshortened): the footprint is the
// anisotropic Gaussian of covariance (a a^T + b b^T) / 4 in texels (Footprint::from_axes).
GlintShade glint_shade(GlintRecord g, vec3 p, float scale, float footprint, vec3 ns, vec3 wo_world,
                       vec3 dpdu_world_x, vec3 dpdu_world_z, vec2 mesh_uv, vec3 mesh_dpdu,
                       vec2 fp_a, vec2 fp_b, out vec3 t_axis, out vec3 b_axis) {
    vec2 uv;
    vec3 dpdu;
    if (g.projection == GLINT_UV_MESH) {
        uv = mesh_uv;
        dpdu = mesh_dpdu;
    } else if (g.projection == GLINT_UV_SPHERICAL) {
        vec3 d = p - vec3(0.5);
        float r = max(length(d), 1e-6);
        float phi = atan(d.z, d.x);
        float theta = acos(clamp(d.y / r, -1.0, 1.0));
        uv = vec2(phi, theta) * r;
        // d/dphi in world: -sin(phi) x + cos(phi) z.
        dpdu = -sin(phi) * dpdu_world_x + cos(phi) * dpdu_world_z;
    } else {
        uv = p.xz;
        dpdu = dpdu_world_x;
    }
    vec3 t = dpdu - ns * dot(ns, dpdu);
    float tl = length(t);
    if (tl < 1e-6) {
        make_frame(ns, t_axis, b_axis);
    } else {
        t_axis = t / tl;
        b_axis = cross(ns, t_axis);
    }
    GlintShade gs;
    gs.stretch = vec2(0.0);
    if (g.projection == GLINT_UV_MESH) {
        gs.u = uv * g.texels_per_unit;
        vec2 a = 0.5 * fp_a * g.texels_per_unit;
        vec2 b = 0.5 * fp_b * g.texels_per_unit;
        float sxx = a.x * a.x + b.x * b.x;
        float sxy = a.x * a.y + b.x * b.y;
        float syy = a.y * a.y + b.y * b.y;
        float half_trace = 0.5 * (sxx + syy);
        float root = sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
        float large = half_trace + root;
        float small = max(half_trace - root, 0.0);
        gs.sigma_p = clamp(sqrt(small), 0.5, g.max_footprint);
        float long_sd = clamp(sqrt(large), gs.sigma_p, g.max_footprint);
        vec2 dir = sxx >= syy ? vec2(large - syy, sxy) : vec2(sxy, large - sxx);
        float dl = length(dir);
        dir = dl > 0.0 ? dir / dl : vec2(1.0, 0.0);
        gs.stretch = dir * sqrt(max(long_sd * long_sd - gs.sigma_p * gs.sigma_p, 0.0));
        return gs;
    }
    gs.u = uv * (scale * g.texels_per_unit);
    float cos_o = max(abs(dot(wo_world, ns)), 0.05);
    gs.sigma_p = clamp(0.5 * footprint / sqrt(cos_o) * g.texels_per_unit, 0.5, g.max_footprint);
    return gs;
}

vec3 glint_eval_local(GlintRecord g, Material m, GlintShade gs, vec3 wo, vec3 wi) {
    if (wi.z <= 0.0 || wo.z <= 0.0) {
        return vec3(0.0);
    }
    vec3 h = normalize(wo + wi);
    uint texels;
    float d = glint_pndf(g.map, g.ranges, gs.u, gs.sigma_p, gs.stretch, h.xy, g.sigma_r, g.prune != 0u, texels);
    vec3 f = fresnel_conductor(dot(wo, h), m.color, m.k);
    return f * (d * ggx_g2(wo, wi, g.shadow_alpha) / (4.0 * wo.z));
}

// f(wo, wi) |cos theta_i| (two-sided, like the conductor).
vec3 glint_eval(GlintRecord g, Material m, GlintShade gs, vec3 wo, vec3 wi) {
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    return glint_eval_local(g, m, gs, wo * flip, wi * flip);
}

// Solid-angle density of glint_sample.
float glint_pdf(GlintRecord g, GlintShade gs, vec3 wo, vec3 wi) {
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    wo *= flip;
    wi *= flip;
    if (wi.z <= 0.0 || wo.z <= 0.0) {
        return 0.0;
    }
    vec3 h = normalize(wo + wi);
    float c = dot(wo, h);
    if (c <= 0.0) {
        return 0.0;
    }
    GlintSampleTexels t = glint_sample_texels(g.map, gs.u, g.sigma_r);
    return glint_sample_pdf(t, h.xy) * h.z / (4.0 * c);
}

bool glint_sample(GlintRecord g, Material m, GlintShade gs, vec3 wo, vec3 u, out BsdfSample s) {
    s = BsdfSample(vec3(0.0), vec3(0.0), 0.0, false);
    if (wo.z == 0.0) {
        return false;
    }
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    wo *= flip;
    GlintSampleTexels t = glint_sample_texels(g.map, gs.u, g.sigma_r);
    vec2 sxy = glint_sample_s(t, u);
    float r2 = dot(sxy, sxy);
    if (r2 >= 1.0) {
        return false;
    }
    vec3 h = vec3(sxy, sqrt(1.0 - r2));
    float c = dot(wo, h);
    if (c <= 0.0) {
        return false;
    }
    vec3 wi = bsdf_reflect(wo, h);
    if (wi.z <= 0.0) {
        return false;
    }
    s.pdf = glint_sample_pdf(t, sxy) * h.z / (4.0 * c);
    if (!(s.pdf > 0.0)) {
        return false;
    }
    s.weight = glint_eval_local(g, m, gs, wo, wi) / s.pdf;
    s.wi = wi * flip;
    return true;
}

#endif
