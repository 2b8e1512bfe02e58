// The P-NDF of a pixel footprint over the infinite map by example, and its importance
// sampling. CPU twins: renderer/src/glint/range_blend.rs (glint_range) and
// renderer/src/glint/pndf.rs (everything else; read it for the formulas).
//
// Every texel i (the integer point u_i) is a Gaussian element in position x normal: normal
// n_i and Jacobian J_i from the point query, positional width SIGMA_H, normal width sigma_r.
// D_P(s) sums the closed-form product integrals of the elements with the footprint Gaussian
// G_P (centre, sigma in texels) over the footprint's box centre +- GLINT_FOOTPRINT_CUTOFF
// sigma. The pruned sum walks aligned power-of-two squares with an explicit stack and drops a
// square whose blended normal interval, widened by glint_pruning_margin, cannot contain s.
#ifndef LAZYSOLID_GLINT_PNDF_GLSL
#define LAZYSOLID_GLINT_PNDF_GLSL

#include "glint/by_example.glsl"

#define GLINT_SIGMA_H 0.4246609
#define GLINT_FOOTPRINT_CUTOFF 3.0
#define GLINT_ROUGHNESS_CUTOFF 4.0
#define GLINT_JACOBIAN_CUTOFF 3.0
#define GLINT_STACK_DEPTH 48
#define GLINT_PI 3.14159265358979

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer GlintRangeEntries { uvec2 v[]; };

// Range of q(f) = (1 - f)^2 + f^2 over [a, b].
vec2 glint_q_range(float a, float b) {
    float qa = (1.0 - a) * (1.0 - a) + a * a;
    float qb = (1.0 - b) * (1.0 - b) + b * b;
    float lo = (a <= 0.5 && b >= 0.5) ? 0.5 : min(qa, qb);
    return vec2(lo, max(qa, qb));
}

float glint_dequantize(uint q) {
    return float(q) / 65535.0 * 2.0 - 1.0;
}

// Interval of the blended normal over the aligned target square [p, p + edge]^2 (edge a power
// of two up to the patch edge, inside one patch) from the range table `entries` (levels of
// size^2 packed entries). False when an example square leaves the table.
bool glint_range(GlintMap m, uint64_t entries, ivec2 p, int edge, out vec2 lo, out vec2 hi) {
    int l = int(m.patch_edge);
    ivec2 cell = ivec2(p.x >= 0 ? p.x / l : -((-p.x + l - 1) / l), p.y >= 0 ? p.y / l : -((-p.y + l - 1) / l));
    ivec2 local = p - cell * l;
    uint level = uint(findLSB(uint(edge)));
    float lf = float(l);
    vec2 f0 = vec2(local) / lf;
    vec2 f1 = f0 + float(edge) / lf;
    vec2 wx0 = vec2(1.0 - f1.x, 1.0 - f0.x);
    vec2 wx1 = vec2(f0.x, f1.x);
    vec2 wy0 = vec2(1.0 - f1.y, 1.0 - f0.y);
    vec2 wy1 = vec2(f0.y, f1.y);
    vec2 qx = glint_q_range(f0.x, f1.x);
    vec2 qy = glint_q_range(f0.y, f1.y);
    bool normalizes = m.mode == GLINT_BLEND_VARIANCE || m.mode == GLINT_BLEND_HISTOGRAM;
    vec2 norm = normalizes ? vec2(sqrt(qx.x * qy.x), sqrt(qx.y * qy.y)) : vec2(1.0);
    lo = vec2(0.0);
    hi = vec2(0.0);
    vec2 none_lo = vec2(1e30);
    vec2 none_hi = vec2(-1e30);
    vec2 hull_lo = vec2(1e30);
    vec2 hull_hi = vec2(-1e30);
    GlintRangeEntries t = GlintRangeEntries(entries);
    for (int i = 0; i < 4; i++) {
        int a = i & 1;
        int b = i >> 1;
        uvec2 o = glint_vertex_origin(m, cell + ivec2(a, b));
        uint px = o.x + uint(local.x + (1 - a) * l);
        uint py = o.y + uint(local.y + (1 - b) * l);
        if (px >= m.size || py >= m.size) {
            return false;
        }
        uvec2 e = t.v[(level * m.size + py) * m.size + px];
        if (e.x == 0xFFFFFFFFu && e.y == 0u) {
            return false;
        }
        vec2 in_lo = vec2(glint_dequantize(e.x & 0xFFFFu), glint_dequantize(e.x >> 16u));
        vec2 in_hi = vec2(glint_dequantize(e.y & 0xFFFFu), glint_dequantize(e.y >> 16u));
        vec2 wxa = a == 0 ? wx0 : wx1;
        vec2 wyb = b == 0 ? wy0 : wy1;
        float w_lo = wxa.x * wyb.x;
        float w_hi = wxa.y * wyb.y;
        if (w_hi > 0.0) {
            hull_lo = min(hull_lo, in_lo);
            hull_hi = max(hull_hi, in_hi);
        }
        if (m.mode == GLINT_BLEND_NONE) {
            if (w_hi >= 0.25) {
                none_lo = min(none_lo, in_lo);
                none_hi = max(none_hi, in_hi);
            }
            continue;
        }
        float c_lo = w_lo / norm.y;
        float c_hi = min(w_hi / norm.x, 1.0);
        for (uint k = 0u; k < 2u; k++) {
            float d;
            float y_lo = glint_normal_to_blend(m, k, in_lo[k], d);
            float y_hi = glint_normal_to_blend(m, k, in_hi[k], d);
            lo[k] += min(c_lo * y_lo, c_hi * y_lo);
            hi[k] += max(c_lo * y_hi, c_hi * y_hi);
        }
    }
    if (m.mode == GLINT_BLEND_NONE) {
        lo = none_lo;
        hi = none_hi;
        return true;
    }
    if (m.mode == GLINT_BLEND_LINEAR) {
        lo = max(lo, hull_lo);
        hi = min(hi, hull_hi);
        return true;
    }
    for (uint k = 0u; k < 2u; k++) {
        float d;
        lo[k] = glint_blend_to_normal(m, k, lo[k], d);
        hi[k] = glint_blend_to_normal(m, k, hi[k], d);
    }
    return true;
}

// Widening of an interval before testing s (see pruning_margin in pndf.rs).
vec2 glint_pruning_margin(vec2 lo, vec2 hi, float sigma_r) {
    return GLINT_ROUGHNESS_CUTOFF * sigma_r + GLINT_JACOBIAN_CUTOFF * GLINT_SIGMA_H * 2.0 * (hi - lo);
}

// One element's integral against a footprint stretched by m (covariance sigma_p^2 I + m m^T;
// see element_stretched in pndf.rs).
float glint_element_stretched(vec2 u_i, vec2 n, mat2 j, vec2 center, float sigma_p, vec2 m, vec2 s,
                              float sigma_r) {
    float ih = 1.0 / (GLINT_SIGMA_H * GLINT_SIGMA_H);
    float ir = 1.0 / (sigma_r * sigma_r);
    float s2 = sigma_p * sigma_p;
    float long2 = s2 + dot(m, m);
    float p00 = (1.0 - m.x * m.x / long2) / s2;
    float p01 = -(m.x * m.y / long2) / s2;
    float p11 = (1.0 - m.y * m.y / long2) / s2;
    vec2 a = s - n;
    vec2 e = center - u_i;
    mat2 jt = transpose(j);
    mat2 mm = jt * j * ir;
    float a00 = mm[0][0] + ih + p00;
    float a01 = mm[1][0] + p01;
    float a11 = mm[1][1] + ih + p11;
    vec2 pe = vec2(p00 * e.x + p01 * e.y, p01 * e.x + p11 * e.y);
    vec2 b = jt * a * ir + pe;
    float c = dot(a, a) * ir + dot(e, pe);
    float det = a00 * a11 - a01 * a01;
    float quad = (a11 * b.x * b.x - 2.0 * a01 * b.x * b.y + a00 * b.y * b.y) / det;
    float ci = 1.0 / (2.0 * GLINT_PI * GLINT_SIGMA_H * GLINT_SIGMA_H * 2.0 * GLINT_PI * sigma_r * sigma_r);
    return ci / (2.0 * GLINT_PI * sigma_p * sqrt(long2)) * (2.0 * GLINT_PI / sqrt(det)) * exp(-0.5 * (c - quad));
}

// One element's integral against the footprint (see element in pndf.rs).
float glint_element(vec2 u_i, vec2 n, mat2 j, vec2 center, float sigma_p, vec2 m, vec2 s, float sigma_r) {
    if (m != vec2(0.0)) {
        return glint_element_stretched(u_i, n, j, center, sigma_p, m, s, sigma_r);
    }
    float ih = 1.0 / (GLINT_SIGMA_H * GLINT_SIGMA_H);
    float ir = 1.0 / (sigma_r * sigma_r);
    float ip = 1.0 / (sigma_p * sigma_p);
    vec2 a = s - n;
    vec2 e = center - u_i;
    mat2 jt = transpose(j);
    mat2 mm = jt * j * ir;
    float a00 = mm[0][0] + ih + ip;
    float a01 = mm[1][0];
    float a11 = mm[1][1] + ih + ip;
    vec2 b = jt * a * ir + e * ip;
    float c = dot(a, a) * ir + dot(e, e) * ip;
    float det = a00 * a11 - a01 * a01;
    float quad = (a11 * b.x * b.x - 2.0 * a01 * b.x * b.y + a00 * b.y * b.y) / det;
    float ci = 1.0 / (2.0 * GLINT_PI * GLINT_SIGMA_H * GLINT_SIGMA_H * 2.0 * GLINT_PI * sigma_r * sigma_r);
    return ci / (2.0 * GLINT_PI * sigma_p * sigma_p) * (2.0 * GLINT_PI / sqrt(det)) * exp(-0.5 * (c - quad));
}

int glint_floor_div(int a, int b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// D_P(s) for the footprint (center, sigma_p, stretch) in texels (covariance sigma_p^2 I +
// stretch stretch^T). prune = false sums every texel of the box (the explicit reference);
// `texels` counts the elements evaluated.
float glint_pndf(GlintMap m, uint64_t entries, vec2 center, float sigma_p, vec2 stretch, vec2 s,
                 float sigma_r, bool prune, out uint texels) {
    texels = 0u;
    vec2 r = vec2(GLINT_FOOTPRINT_CUTOFF * sigma_p);
    if (stretch != vec2(0.0)) {
        float s2 = sigma_p * sigma_p;
        r = vec2(sqrt(s2 + stretch.x * stretch.x), sqrt(s2 + stretch.y * stretch.y)) * GLINT_FOOTPRINT_CUTOFF;
    }
    ivec2 lo = ivec2(ceil(center - r));
    ivec2 hi = ivec2(floor(center + r));
    if (lo.x > hi.x || lo.y > hi.y) {
        return 0.0;
    }
    float sum = 0.0;
    if (!prune) {
        for (int y = lo.y; y <= hi.y; y++) {
            for (int x = lo.x; x <= hi.x; x++) {
                vec2 u = vec2(x, y);
                GlintPoint q = glint_point(m, u);
                sum += glint_element(u, q.normal, q.jacobian_exact, center, sigma_p, stretch, s, sigma_r);
                texels++;
            }
        }
        return sum;
    }
    ivec2 ext = hi - lo + 1;
    int extent = max(ext.x, ext.y);
    int edge0 = int(min(uint(1) << uint(findMSB(uint(max(extent, 1)) * 2u - 1u)), m.patch_edge));
    ivec2 s0 = ivec2(glint_floor_div(lo.x, edge0), glint_floor_div(lo.y, edge0));
    ivec2 s1 = ivec2(glint_floor_div(hi.x, edge0), glint_floor_div(hi.y, edge0));
    ivec3 stack[GLINT_STACK_DEPTH];
    for (int sy = s0.y; sy <= s1.y; sy++) {
        for (int sx = s0.x; sx <= s1.x; sx++) {
            int top = 0;
            stack[top++] = ivec3(sx * edge0, sy * edge0, edge0);
            while (top > 0) {
                ivec3 sq = stack[--top];
                ivec2 p = sq.xy;
                int edge = sq.z;
                if (p.x > hi.x || p.y > hi.y || p.x + edge <= lo.x || p.y + edge <= lo.y) {
                    continue;
                }
                if (edge == 1) {
                    texels++;
                    vec2 u = vec2(p);
                    GlintPoint q = glint_point(m, u);
                    sum += glint_element(u, q.normal, q.jacobian_exact, center, sigma_p, stretch, s, sigma_r);
                    continue;
                }
                vec2 ilo, ihi;
                if (!glint_range(m, entries, p, edge, ilo, ihi)) {
                    continue;
                }
                if (!(all(greaterThanEqual(s, ilo)) && all(lessThanEqual(s, ihi)))) {
                    vec2 mg = glint_pruning_margin(ilo, ihi, sigma_r);
                    if (!(all(greaterThanEqual(s, ilo - mg)) && all(lessThanEqual(s, ihi + mg)))) {
                        continue;
                    }
                }
                int h = edge / 2;
                stack[top++] = ivec3(p + ivec2(h, h), h);
                stack[top++] = ivec3(p + ivec2(0, h), h);
                stack[top++] = ivec3(p + ivec2(h, 0), h);
                stack[top++] = ivec3(p, h);
            }
        }
    }
    return sum;
}

// The 4 texels around a shading point: bilinear weights, normals and the covariances
// sigma_r^2 I + SIGMA_H^2 J J^T of their normal marginals (see SampleTexels in pndf.rs).
struct GlintSampleTexels {
    vec4 weights;
    vec2 normals[4];
    mat2 covariances[4];
};

GlintSampleTexels glint_sample_texels(GlintMap m, vec2 u, float sigma_r) {
    vec2 base = floor(u);
    vec2 f = u - base;
    vec2 wx = vec2(1.0 - f.x, f.x);
    vec2 wy = vec2(1.0 - f.y, f.y);
    GlintSampleTexels t;
    for (int i = 0; i < 4; i++) {
        int a = i & 1;
        int b = i >> 1;
        GlintPoint q = glint_point(m, base + vec2(a, b));
        t.weights[i] = wx[a] * wy[b];
        t.normals[i] = q.normal;
        mat2 j = q.jacobian_exact;
        t.covariances[i] = j * transpose(j) * (GLINT_SIGMA_H * GLINT_SIGMA_H) + mat2(sigma_r * sigma_r);
    }
    return t;
}

// Draws s with u in [0, 1)^3 (u.z picks the texel).
vec2 glint_sample_s(GlintSampleTexels t, vec3 u) {
    int pick = 3;
    float acc = 0.0;
    for (int i = 0; i < 4; i++) {
        acc += t.weights[i];
        if (u.z < acc) {
            pick = i;
            break;
        }
    }
    float r = sqrt(-2.0 * log(1.0 - u.x));
    float phi = 2.0 * GLINT_PI * u.y;
    vec2 z = vec2(r * cos(phi), r * sin(phi));
    mat2 c = t.covariances[pick];
    float l00 = sqrt(c[0][0]);
    float l10 = c[0][1] / l00;
    float l11 = sqrt(max(c[1][1] - l10 * l10, 0.0));
    return t.normals[pick] + vec2(l00 * z.x, l10 * z.x + l11 * z.y);
}

// Density of s under glint_sample_s.
float glint_sample_pdf(GlintSampleTexels t, vec2 s) {
    float p = 0.0;
    for (int i = 0; i < 4; i++) {
        if (t.weights[i] > 0.0) {
            mat2 c = t.covariances[i];
            float det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
            vec2 d = s - t.normals[i];
            vec2 inv_d = vec2(c[1][1] * d.x - c[1][0] * d.y, -c[0][1] * d.x + c[0][0] * d.y) / det;
            p += t.weights[i] * exp(-0.5 * dot(d, inv_d)) / (2.0 * GLINT_PI * sqrt(det));
        }
    }
    return p;
}

#endif
