// Normal maps filtered by mixtures of von Mises-Fisher lobes (seed 000 ch. 7; CPU fit in
// renderer/src/normal_map): the texel's mixture is chosen stochastically over the ray's
// footprint, and shading sums the material's BSDF over the lobes, each lobe's spread convolved
// with the BSDF in closed form.
//
// Bindings (block names, bound by renderer::image_texture::DeviceImages::vmf_bindings):
//   VmfRecords  first lobe of each level, per vMF-filtered normal map
//   VmfLobes    VMF_LOBES lobes (alpha, alpha * r) per texel of every level
// Needs render/image.glsl, render/bsdf.glsl and the spec constant VMF_LOBES (>= 1).
#ifndef LAZYSOLID_RENDER_NORMAL_VMF_GLSL
#define LAZYSOLID_RENDER_NORMAL_VMF_GLSL

struct VmfRecord {
    uint level_offset[IMAGE_MAX_LEVELS];
    uint pad0, pad1;
};
layout(binding = 18, scalar) readonly buffer VmfRecords { VmfRecord vmf_records[]; };
layout(binding = 19, scalar) readonly buffer VmfLobes { vec4 vmf_lobes[]; };

// A texel's mixture in world space: weights, mean directions and concentrations.
struct VmfShade {
    // VMF_MAX_LOBES entries (a struct with arrays sized by a specialization constant cannot
    // be assigned); loops run to VMF_LOBES, a constant once specialized, so they unroll.
    float alpha[VMF_MAX_LOBES];
    vec3 mu[VMF_MAX_LOBES];
    float kappa[VMF_MAX_LOBES];
};

// First lobe of one texel drawn over the footprint (uv, axes a and b) with probability equal to
// its weight in image_lookup's anisotropic trilinear filter: a tap along the long axis, then
// one of the two levels, then one of the four bilinear texels (stochastic texture filtering).
// Averaged over samples, the drawn mixtures are the filtered mixture.
uint vmf_texel(uint img, vec2 uv, vec2 a, vec2 b, vec3 u) {
    vec2 axis;
    float n;
    float lod;
    image_footprint_taps(img, a, b, axis, n, lod);
    lod = clamp(lod, 0.0, float(image_records[img].levels - 1u));
    float tap = min(floor(u.x * n), n - 1.0);
    float v = u.x * n - tap;  // still uniform in [0, 1)
    vec2 p = uv + axis * ((tap + 0.5) / n - 0.5);
    float l0 = floor(lod);
    uint l = uint(l0) + (v < lod - l0 ? 1u : 0u);
    uvec2 ls = image_level_size(img, l);
    float x = p.x * float(ls.x) - 0.5;
    float y = (1.0 - p.y) * float(ls.y) - 0.5;
    float x0 = floor(x);
    float y0 = floor(y);
    int xi = int(x0) + (u.y < x - x0 ? 1 : 0);
    int yi = int(y0) + (u.z < y - y0 ? 1 : 0);
    int w = int(ls.x);
    int h = int(ls.y);
    uint xw = min(uint(xi - w * int(floor(float(xi) / float(w)))), ls.x - 1u);
    uint yw = min(uint(yi - h * int(floor(float(yi) / float(h)))), ls.y - 1u);
    return vmf_records[image_records[img].vmf_record].level_offset[l] + (yw * ls.x + xw) * uint(VMF_LOBES);
}

// The mean length A(kappa) = coth kappa - 1/kappa of a lobe.
float vmf_mean_length(float kappa) {
    if (kappa < 1e-3) {
        return kappa / 3.0;
    }
    if (kappa > 20.0) {
        return 1.0 - 1.0 / kappa;
    }
    return 1.0 / tanh(kappa) - 1.0 / kappa;
}

// The lobes of the texel starting at `first`, moved from tangent space (t, bt, n) to world and
// kept facing the viewer wo as a single mapped normal is (facing_normal), so that the finest
// level, one sharp lobe per texel, shades exactly as the unfiltered map. kappa from |r| by
// Banerjee's approximation, as the fit's M-step computes it.
VmfShade vmf_shade(uint first, vec3 t, vec3 bt, vec3 n, vec3 wo) {
    VmfShade v;
    for (uint j = 0u; j < uint(VMF_LOBES); j++) {
        vec4 lobe = vmf_lobes[first + j];
        float alpha = lobe.x;
        vec3 r = alpha > 0.0 ? lobe.yzw / alpha : vec3(0.0, 0.0, 1.0);
        float len = length(r);
        v.alpha[j] = len > 0.0 ? alpha : 0.0;
        vec3 mu = len > 0.0 ? r / len : vec3(0.0, 0.0, 1.0);
        v.mu[j] = facing_normal(n, normalize(t * mu.x + bt * mu.y + n * mu.z), wo);
        float rl = min(len, 0.999999);
        v.kappa[j] = min((3.0 * rl - rl * rl * rl) / (1.0 - rl * rl), float(VMF_MAX_KAPPA));
    }
    return v;
}

// The error function (Abramowitz and Stegun 7.1.26; renderer::normal_map::vmf::erf).
float vmf_erf(float x) {
    float t = 1.0 / (1.0 + 0.3275911 * abs(x));
    float poly = ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t;
    return sign(x) * (1.0 - poly * exp(-x * x));
}

// E[max(0, n . l)] over a lobe of concentration kappa whose axis makes the cosine t with l:
// n . l taken as normal with the lobe's exact mean and variance, whose clamped mean is
// m Phi(m / sd) + sd phi(m / sd) (renderer::normal_map::vmf::clamped_cosine_mean, within 0.01
// of the integral from kappa = 5 on).
float vmf_clamped_cosine(float t, float kappa) {
    float a = vmf_mean_length(kappa);
    float m = a * t;
    float var = t * t * (1.0 - 2.0 * a / kappa - a * a) + (1.0 - t * t) * a / kappa;
    float sd = sqrt(max(var, 1e-12));
    float z = m / sd;
    float density = exp(-0.5 * z * z) * 0.3989422804;
    float cdf = 0.5 * (1.0 + vmf_erf(z * 0.7071067812));
    return m * cdf + sd * density;
}

// The material of lobe j: a conductor's GGX lobe widened by the lobe's spread, alpha'^2 =
// alpha^2 + 2 / kappa (the closed-form convolution kappa' = kappa s / (kappa + s) of seed 000
// Eq. 7.20 with the GGX lobe read as a vMF of s = 2 / alpha^2); a plastic's coat keeps its
// roughness (its tabulated coat albedo depends on it) and turns only.
Material vmf_lobe_material(Material m, float kappa) {
    if (material_is(m, MATERIAL_CONDUCTOR)) {
        float a = bsdf_alpha(m);
        float widened = max(sqrt(a * a + 2.0 / kappa), 2.0 * GGX_MIN_ALPHA);
        m.roughness = sqrt(widened);
    }
    return m;
}

// The albedo of lobe j under a plastic coat: the diffuse response of normals spread about mu is
// A(kappa) (mu . l) where no normal of the lobe faces away from the light (the mean of n . l is
// r . l). A Lambertian lobe has its exact clamped response instead (vmf_eval).
vec3 vmf_lobe_albedo(vec3 albedo, float kappa) {
    return albedo * vmf_mean_length(kappa);
}

// f |cos| and the solid-angle pdf of the mixture BSDF (world directions). Lobes that face away
// from the viewer contribute nothing (the map's texels that do are not seen).
vec3 vmf_eval(Material m, vec3 albedo, VmfShade v, vec3 wo, vec3 wi, out float pdf) {
    vec3 f = vec3(0.0);
    pdf = 0.0;
    float seen = 0.0;
    for (uint j = 0u; j < uint(VMF_LOBES); j++) {
        vec3 t;
        vec3 b;
        make_frame(v.mu[j], t, b);
        vec3 wo_l = vec3(dot(wo, t), dot(wo, b), dot(wo, v.mu[j]));
        if (v.alpha[j] > 0.0 && wo_l.z > 0.0) {
            vec3 wi_l = vec3(dot(wi, t), dot(wi, b), dot(wi, v.mu[j]));
            if (material_is(m, MATERIAL_LAMBERTIAN)) {
                // Lambert's law averaged over the lobe, clamp included: at a grazing light the
                // lobe's normals that still face it keep the surface lit (seed 000 Fig. 7.3).
                f += v.alpha[j] * albedo * (vmf_clamped_cosine(wi_l.z, v.kappa[j]) / PI);
                pdf += v.alpha[j] * pdf_cosine_hemisphere(wi_l.z);
            } else {
                Material mj = vmf_lobe_material(m, v.kappa[j]);
                vec3 aj = vmf_lobe_albedo(albedo, v.kappa[j]);
                f += v.alpha[j] * bsdf_eval(mj, aj, wo_l, wi_l);
                pdf += v.alpha[j] * bsdf_pdf(mj, aj, wo_l, wi_l);
            }
            seen += v.alpha[j];
        }
    }
    pdf = seen > 0.0 ? pdf / seen : 0.0;
    return f;
}

// Samples the mixture: a lobe facing the viewer by weight, then its BSDF; the weight and pdf
// are the whole mixture's (one-sample MIS over the lobes).
bool vmf_sample(Material m, vec3 albedo, VmfShade v, vec3 wo, vec3 u, float u_lobe, out BsdfSample s) {
    s = BsdfSample(vec3(0.0), vec3(0.0), 0.0, false);
    float seen = 0.0;
    for (uint j = 0u; j < uint(VMF_LOBES); j++) {
        if (v.alpha[j] > 0.0 && dot(wo, v.mu[j]) > 0.0) {
            seen += v.alpha[j];
        }
    }
    if (seen <= 0.0) {
        return false;
    }
    float pick = u_lobe * seen;
    vec3 mu = vec3(0.0);
    float kappa = 1.0;
    bool found = false;
    for (uint j = 0u; j < uint(VMF_LOBES); j++) {
        if (!found && v.alpha[j] > 0.0 && dot(wo, v.mu[j]) > 0.0) {
            mu = v.mu[j];
            kappa = v.kappa[j];
            pick -= v.alpha[j];
            found = pick < 0.0;
        }
    }
    vec3 t;
    vec3 b;
    make_frame(mu, t, b);
    vec3 wo_l = vec3(dot(wo, t), dot(wo, b), dot(wo, mu));
    BsdfSample lobe;
    if (!bsdf_sample(vmf_lobe_material(m, kappa), vmf_lobe_albedo(albedo, kappa), wo_l, u, lobe) || lobe.specular) {
        return false;
    }
    vec3 wi = t * lobe.wi.x + b * lobe.wi.y + mu * lobe.wi.z;
    float pdf;
    vec3 f = vmf_eval(m, albedo, v, wo, wi, pdf);
    if (pdf <= 0.0) {
        return false;
    }
    s.wi = wi;
    s.pdf = pdf;
    s.weight = f / pdf;
    return true;
}

#endif
