// BSDFs of the path tracer, in the local shading frame: z is the surface's outward normal (not
// flipped towards the viewer) and wo points from the surface back along the path. Opaque
// materials are two-sided (the frame is mirrored when wo.z < 0); a dielectric reads wo.z's sign
// to know whether the path enters (wo.z > 0) or leaves it.
//
// Conventions: bsdf_eval returns f(wo, wi) |cos theta_i| of the non-delta lobes; bsdf_pdf the
// solid-angle density with which bsdf_sample produces wi through them, lobe choice included; a
// sample's weight is f |cos theta_i| / pdf. A delta sample (specular = true) reports as pdf the
// discrete probability of its lobe choice. The 1/eta^2 radiance scaling of refraction is left
// out: it cancels on every path that enters and leaves the same medium, and without it the
// weights of lossless glass sum to one. CPU twin: renderer/src/shading/reference/bsdf.rs.
#ifndef LAZYSOLID_RENDER_BSDF_GLSL
#define LAZYSOLID_RENDER_BSDF_GLSL

#include "render/math.glsl"
#include "render/sampling.glsl"
#include "render/material.glsl"
#include "render/fresnel.glsl"
#include "render/microfacet.glsl"

struct BsdfSample {
    vec3 wi;       // sampled direction (local frame)
    vec3 weight;   // f |cos theta_i| / pdf
    float pdf;     // solid-angle pdf, or the lobe probability of a delta sample
    bool specular; // sampled a delta lobe: no next-event estimation, no MIS
};

// True when m is of kind `kind`, false without a load when the kernel compiled that kind out.
bool material_is(Material m, uint kind) {
    return material_kind_used(kind) && m.kind == kind;
}

// GGX alpha of a material.
float bsdf_alpha(Material m) {
    return m.roughness * m.roughness;
}

// True when the material's GGX lobe is a delta (perfect mirror or smooth glass/coat).
bool bsdf_is_smooth(Material m) {
    return bsdf_alpha(m) < GGX_MIN_ALPHA;
}

// True when next-event estimation is useful: the material has a non-delta lobe.
bool bsdf_has_smooth_lobe(Material m) {
    if (material_is(m, MATERIAL_LAMBERTIAN) || material_is(m, MATERIAL_PLASTIC)) {
        return true;
    }
    if (material_is(m, MATERIAL_CONDUCTOR) || material_is(m, MATERIAL_DIELECTRIC)) {
        return !bsdf_is_smooth(m);
    }
    return false;
}

// Mirror direction of wo about the local normal.
vec3 bsdf_mirror(vec3 wo) {
    return vec3(-wo.x, -wo.y, wo.z);
}

// Mirror direction of wo about the microfacet normal h.
vec3 bsdf_reflect(vec3 wo, vec3 h) {
    return 2.0 * dot(wo, h) * h - wo;
}

// Refraction of wo (wo.n > 0) through n with eta = n_t / n_i; false under total internal
// reflection.
bool bsdf_refract(vec3 wo, vec3 n, float eta, out vec3 wi) {
    float c = dot(wo, n);
    float s2 = max(0.0, 1.0 - c * c) / (eta * eta);
    if (s2 >= 1.0) {
        wi = vec3(0.0);
        return false;
    }
    float ct = sqrt(1.0 - s2);
    wi = -wo / eta + (c / eta - ct) * n;
    return true;
}

// Plastic: a diffuse base of albedo rho under a dielectric coat of index eta, smooth or GGX.
// The smooth coat is the usual smooth plastic (Mitsuba's with its nonlinear internal
// scattering); a rough coat transmits what its GGX lobe does not reflect, as in the coupled
// model of Kelemen and Szirmay-Kalos (2001). Light the coat does not reflect, 1 - E(cos),
// enters, is scattered by the base and leaves through the coat after any number of internal
// bounces:
//   f_base cos_i = rho (1 - E(cos_o)) (1 - E(cos_i)) cos_i / (pi eta^2 (1 - rho F_in)),
// where E is the coat's directional albedo (Fresnel for a smooth coat, the tabulated
// single-scattering GGX reflectance for a rough one) and F_in = 1 - (1/eta^2) int (1 - E) 2 mu
// dmu is the share of the base's diffuse light that the coat sends back down. With rho = 1 the
// coat and base together reflect exactly 1: what the coat does not reflect, the base returns.
// Host side (tables, F_in): renderer/src/shading/coat.rs.

// Directional albedo of the coat seen at cos_theta (>= 0).
float plastic_coat_albedo(Material m, float cos_theta) {
    if (bsdf_is_smooth(m)) {
        return fresnel_dielectric(cos_theta, m.ior);
    }
    uint last = uint(PLASTIC_COAT_KNOTS) - 1u;
    float x = sqrt(clamp(cos_theta, 0.0, 1.0)) * float(last);
    uint i = min(uint(x), last - 1u);
    uint j = i + 1u;
    float a = m.coat_albedo[i >> 2u][i & 3u];
    float b = m.coat_albedo[j >> 2u][j & 3u];
    return a + (b - a) * (x - float(i));
}

// Probability that plastic samples its coat rather than its base: the coat's reflectance
// against the light the base can send back.
float plastic_specular_probability(float coat, vec3 albedo) {
    float d = (1.0 - coat) * (albedo.x + albedo.y + albedo.z) * (1.0 / 3.0);
    float s = coat + d;
    return s > 0.0 ? coat / s : 1.0;
}

// ---- Opaque lobes, for wo.z > 0 (the caller mirrors the frame) ----

vec3 lambertian_eval(vec3 albedo, vec3 wo, vec3 wi) {
    return wi.z > 0.0 ? albedo * (wi.z * INV_PI) : vec3(0.0);
}

vec3 conductor_eval(Material m, vec3 wo, vec3 wi) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA || wi.z <= 0.0) {
        return vec3(0.0);
    }
    vec3 h = normalize(wo + wi);
    vec3 f = fresnel_conductor(dot(wo, h), m.color, m.k);
    return f * (ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0 * wo.z));
}

float conductor_pdf(Material m, vec3 wo, vec3 wi) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA || wi.z <= 0.0) {
        return 0.0;
    }
    vec3 h = normalize(wo + wi);
    return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0 * wo.z);
}

bool conductor_sample(Material m, vec3 wo, vec3 u, inout BsdfSample s) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA) {
        s.wi = bsdf_mirror(wo);
        s.weight = fresnel_conductor(wo.z, m.color, m.k);
        s.pdf = 1.0;
        s.specular = true;
        return true;
    }
    vec3 h = ggx_sample_vndf(wo, alpha, u.xy);
    float c = dot(wo, h);
    s.wi = bsdf_reflect(wo, h);
    if (c <= 0.0 || s.wi.z <= 0.0) {
        return false;
    }
    s.weight = fresnel_conductor(c, m.color, m.k) * (ggx_g2(wo, s.wi, alpha) / ggx_g1(wo, alpha));
    s.pdf = conductor_pdf(m, wo, s.wi);
    return s.pdf > 0.0;
}

vec3 plastic_eval(Material m, vec3 albedo, vec3 wo, vec3 wi) {
    if (wi.z <= 0.0) {
        return vec3(0.0);
    }
    float to = 1.0 - plastic_coat_albedo(m, wo.z);
    float ti = 1.0 - plastic_coat_albedo(m, wi.z);
    vec3 f = albedo * (to * ti * wi.z * INV_PI / (m.ior * m.ior)) / (1.0 - albedo * m.coat_internal);
    float alpha = bsdf_alpha(m);
    if (alpha >= GGX_MIN_ALPHA) {
        vec3 h = normalize(wo + wi);
        float fh = fresnel_dielectric(dot(wo, h), m.ior);
        f += vec3(fh * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0 * wo.z));
    }
    return f;
}

float plastic_pdf(Material m, vec3 albedo, vec3 wo, vec3 wi) {
    if (wi.z <= 0.0) {
        return 0.0;
    }
    float p = plastic_specular_probability(plastic_coat_albedo(m, wo.z), albedo);
    float pdf = (1.0 - p) * wi.z * INV_PI;
    float alpha = bsdf_alpha(m);
    if (alpha >= GGX_MIN_ALPHA) {
        vec3 h = normalize(wo + wi);
        pdf += p * ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0 * wo.z);
    }
    return pdf;
}

bool plastic_sample(Material m, vec3 albedo, vec3 wo, vec3 u, inout BsdfSample s) {
    float coat = plastic_coat_albedo(m, wo.z);
    float p = plastic_specular_probability(coat, albedo);
    float alpha = bsdf_alpha(m);
    if (u.z < p) {
        if (alpha < GGX_MIN_ALPHA) {
            s.wi = bsdf_mirror(wo);
            s.weight = vec3(coat / p);
            s.pdf = p;
            s.specular = true;
            return true;
        }
        s.wi = bsdf_reflect(wo, ggx_sample_vndf(wo, alpha, u.xy));
    } else {
        s.wi = sample_cosine_hemisphere(u.xy);
    }
    if (s.wi.z <= 0.0) {
        return false;
    }
    s.pdf = plastic_pdf(m, albedo, wo, s.wi);
    if (s.pdf <= 0.0) {
        return false;
    }
    s.weight = plastic_eval(m, albedo, wo, s.wi) / s.pdf;
    return true;
}

// ---- Dielectric, for wo.z > 0 with eta = n(wi side below) / n(wo side) ----

// Generalized half vector of a refraction pair, on wo's side; false when the pair cannot be a
// refraction through any microfacet.
bool dielectric_half_vector(vec3 wo, vec3 wi, float eta, out vec3 h) {
    h = wo + eta * wi;
    float len2 = dot(h, h);
    if (len2 <= 0.0) {
        return false;
    }
    h = h / sqrt(len2);
    if (h.z < 0.0) {
        h = -h;
    }
    return dot(wo, h) > 0.0 && dot(wi, h) < 0.0;
}

vec3 dielectric_eval(Material m, vec3 tint, vec3 wo, vec3 wi, float eta) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA || wi.z == 0.0) {
        return vec3(0.0);
    }
    if (wi.z > 0.0) {
        vec3 h = normalize(wo + wi);
        float f = fresnel_dielectric(dot(wo, h), eta);
        return vec3(f * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0 * wo.z));
    }
    vec3 h;
    if (!dielectric_half_vector(wo, wi, eta, h)) {
        return vec3(0.0);
    }
    float c = dot(wo, h);
    float ci = dot(wi, h);
    float denom = c + eta * ci;
    float f = fresnel_dielectric(c, eta);
    float value = (1.0 - f) * ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) * eta * eta * (-ci) * c
        / (wo.z * denom * denom);
    return tint * value;
}

float dielectric_pdf(Material m, vec3 wo, vec3 wi, float eta) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA || wi.z == 0.0) {
        return 0.0;
    }
    if (wi.z > 0.0) {
        vec3 h = normalize(wo + wi);
        float f = fresnel_dielectric(dot(wo, h), eta);
        return f * ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0 * wo.z);
    }
    vec3 h;
    if (!dielectric_half_vector(wo, wi, eta, h)) {
        return 0.0;
    }
    float c = dot(wo, h);
    float ci = dot(wi, h);
    float denom = c + eta * ci;
    float f = fresnel_dielectric(c, eta);
    return (1.0 - f) * ggx_g1(wo, alpha) * c * ggx_d(h, alpha) / wo.z * eta * eta * (-ci)
        / (denom * denom);
}

bool dielectric_sample(Material m, vec3 tint, vec3 wo, float eta, vec3 u, inout BsdfSample s) {
    float alpha = bsdf_alpha(m);
    if (alpha < GGX_MIN_ALPHA) {
        float f = fresnel_dielectric(wo.z, eta);
        s.specular = true;
        if (u.z < f) {
            s.wi = bsdf_mirror(wo);
            s.weight = vec3(1.0);
            s.pdf = f;
            return true;
        }
        if (!bsdf_refract(wo, vec3(0.0, 0.0, 1.0), eta, s.wi)) {
            return false;
        }
        s.weight = tint;
        s.pdf = 1.0 - f;
        return true;
    }
    vec3 h = ggx_sample_vndf(wo, alpha, u.xy);
    float c = dot(wo, h);
    if (c <= 0.0) {
        return false;
    }
    float f = fresnel_dielectric(c, eta);
    if (u.z < f) {
        s.wi = bsdf_reflect(wo, h);
        if (s.wi.z <= 0.0) {
            return false;
        }
        s.weight = vec3(ggx_g2(wo, s.wi, alpha) / ggx_g1(wo, alpha));
    } else {
        if (!bsdf_refract(wo, h, eta, s.wi) || s.wi.z >= 0.0) {
            return false;
        }
        s.weight = tint * (ggx_g2(wo, s.wi, alpha) / ggx_g1(wo, alpha));
    }
    s.pdf = dielectric_pdf(m, wo, s.wi, eta);
    return s.pdf > 0.0;
}

// ---- Entry points ----

// z sign that maps the path's side of an opaque surface to +z.
float bsdf_side(vec3 wo) {
    return wo.z < 0.0 ? -1.0 : 1.0;
}

// f(wo, wi) |cos theta_i| of the non-delta lobes.
vec3 bsdf_eval(Material m, vec3 albedo, vec3 wo, vec3 wi) {
    if (wo.z == 0.0) {
        return vec3(0.0);
    }
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    wo *= flip;
    wi *= flip;
    if (material_is(m, MATERIAL_LAMBERTIAN)) {
        return lambertian_eval(albedo, wo, wi);
    }
    if (material_is(m, MATERIAL_CONDUCTOR)) {
        return conductor_eval(m, wo, wi);
    }
    if (material_is(m, MATERIAL_PLASTIC)) {
        return plastic_eval(m, albedo, wo, wi);
    }
    if (material_is(m, MATERIAL_DIELECTRIC)) {
        float eta = flip.z > 0.0 ? m.ior : 1.0 / m.ior;
        return dielectric_eval(m, albedo, wo, wi, eta);
    }
    return vec3(0.0);
}

// Solid-angle density with which bsdf_sample produces wi through its non-delta lobes.
float bsdf_pdf(Material m, vec3 albedo, vec3 wo, vec3 wi) {
    if (wo.z == 0.0) {
        return 0.0;
    }
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    wo *= flip;
    wi *= flip;
    if (material_is(m, MATERIAL_LAMBERTIAN)) {
        return pdf_cosine_hemisphere(wi.z);
    }
    if (material_is(m, MATERIAL_CONDUCTOR)) {
        return conductor_pdf(m, wo, wi);
    }
    if (material_is(m, MATERIAL_PLASTIC)) {
        return plastic_pdf(m, albedo, wo, wi);
    }
    if (material_is(m, MATERIAL_DIELECTRIC)) {
        float eta = flip.z > 0.0 ? m.ior : 1.0 / m.ior;
        return dielectric_pdf(m, wo, wi, eta);
    }
    return 0.0;
}

// Samples wi with u in [0,1)^3 (u.z chooses the lobe); false when the path is absorbed.
bool bsdf_sample(Material m, vec3 albedo, vec3 wo, vec3 u, out BsdfSample s) {
    s = BsdfSample(vec3(0.0), vec3(0.0), 0.0, false);
    if (wo.z == 0.0) {
        return false;
    }
    vec3 flip = vec3(1.0, 1.0, bsdf_side(wo));
    wo *= flip;
    bool ok = false;
    if (material_is(m, MATERIAL_LAMBERTIAN)) {
        s.wi = sample_cosine_hemisphere(u.xy);
        s.pdf = pdf_cosine_hemisphere(s.wi.z);
        s.weight = albedo;
        ok = s.pdf > 0.0;
    } else if (material_is(m, MATERIAL_CONDUCTOR)) {
        ok = conductor_sample(m, wo, u, s);
    } else if (material_is(m, MATERIAL_PLASTIC)) {
        ok = plastic_sample(m, albedo, wo, u, s);
    } else if (material_is(m, MATERIAL_DIELECTRIC)) {
        float eta = flip.z > 0.0 ? m.ior : 1.0 / m.ior;
        ok = dielectric_sample(m, albedo, wo, eta, u, s);
    }
    s.wi *= flip;
    return ok;
}

#endif
