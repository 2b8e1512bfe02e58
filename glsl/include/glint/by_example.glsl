// The infinite normal map by example of the glint microstructure (point queries): the target
// plane is a grid of target patches of edge l; each grid vertex hashes to the origin of an
// example patch of edge 2l (one seed per vertex, so the four cells around it agree and the map
// has no seams), and a point blends its cell's four corner patches with bilinear weights:
// none (nearest vertex), linear, variance preserving or histogram preserving (Gaussianization
// tables G, G^-1). The Jacobian follows by the chain rule (Eqs. 7-12 of the paper, with the
// derivative of G^-1); the exact one adds the weights' variation, which the paper ignores.
// CPU twin: renderer/src/glint/by_example.rs (read it for the derivation).
#ifndef LAZYSOLID_GLINT_BY_EXAMPLE_GLSL
#define LAZYSOLID_GLINT_BY_EXAMPLE_GLSL

#include "render/rng.glsl"

struct GlintMap {
    uint64_t texels;   // size * size vec2 (n_x, n_y), row by row
    uint64_t tables;   // G_x, G_y, G^-1_x, G^-1_y: GLINT_TABLE_KNOTS floats each
    uint size;         // example edge
    uint patch_edge;       // target patch edge l
    uint seed;         // hash seed of the vertex origins
    uint mode;         // GLINT_BLEND_*
    vec2 forward_lo;   // domain of G per component
    vec2 forward_hi;
    float inverse_max; // domain of G^-1: [-inverse_max, inverse_max]
    vec2 mean;         // example mean (variance-preserving blending)
};

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer GlintTexels { vec2 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer GlintTables { float v[]; };

struct GlintPoint {
    vec2 normal;        // (n_x, n_y)
    mat2 jacobian;      // Eqs. 10-12 (columns d/dx, d/dy)
    mat2 jacobian_exact; // with the weights' variation
};

// Origin of grid vertex v's example patch: uniform in [0, size - 2l) per axis.
uvec2 glint_vertex_origin(GlintMap m, ivec2 v) {
    uint range = m.size - 2u * m.patch_edge;
    uint h = rng_hash(uint(v.x) ^ rng_hash(uint(v.y) ^ rng_hash(m.seed)));
    return uvec2(h % range, rng_hash(h) % range);
}

// Bilinear read of the example at p (0 <= p < size - 1) with its Jacobian.
vec2 glint_example_sample(GlintMap m, vec2 p, out mat2 jac) {
    GlintTexels t = GlintTexels(m.texels);
    float x0 = floor(p.x);
    float y0 = floor(p.y);
    float tx = p.x - x0;
    float ty = p.y - y0;
    uint i = uint(y0) * m.size + uint(x0);
    vec2 t00 = t.v[i];
    vec2 t10 = t.v[i + 1u];
    vec2 t01 = t.v[i + m.size];
    vec2 t11 = t.v[i + m.size + 1u];
    vec2 bottom = t00 + (t10 - t00) * tx;
    vec2 top = t01 + (t11 - t01) * tx;
    vec2 d_dx = (t10 - t00) + ((t11 - t01) - (t10 - t00)) * ty;
    jac = mat2(d_dx, top - bottom);
    return bottom + (top - bottom) * ty;
}

// Piecewise-linear table `which` (0, 1: G; 2, 3: G^-1) over [lo, hi]: value, and its slope
// (0 outside the domain) in `slope`.
float glint_table(GlintMap m, uint which, float lo, float hi, float x, out float slope) {
    GlintTables t = GlintTables(m.tables);
    float last = float(GLINT_TABLE_KNOTS - 1u);
    float step_ = (hi - lo) / last;
    float s = clamp((x - lo) / step_, 0.0, last);
    float j = min(floor(s), last - 1.0);
    float f = s - j;
    uint base = which * GLINT_TABLE_KNOTS + uint(j);
    float a = t.v[base];
    float b = t.v[base + 1u];
    slope = (x < lo || x > hi) ? 0.0 : (b - a) / step_;
    return a + f * (b - a);
}

// Component k of an input value in blend space, with its derivative.
float glint_normal_to_blend(GlintMap m, uint k, float v, out float d) {
    d = 1.0;
    if (m.mode == GLINT_BLEND_VARIANCE) {
        return v - m.mean[k];
    }
    if (m.mode == GLINT_BLEND_HISTOGRAM) {
        return glint_table(m, k, m.forward_lo[k], m.forward_hi[k], v, d);
    }
    return v;
}

// Component k of a blended value back in normal space, with its derivative.
float glint_blend_to_normal(GlintMap m, uint k, float s, out float d) {
    d = 1.0;
    if (m.mode == GLINT_BLEND_VARIANCE) {
        return s + m.mean[k];
    }
    if (m.mode == GLINT_BLEND_HISTOGRAM) {
        return glint_table(m, 2u + k, -m.inverse_max, m.inverse_max, s, d);
    }
    return s;
}

// The normal and Jacobians of the infinite map at target point u (texels).
GlintPoint glint_point(GlintMap m, vec2 u) {
    float l = float(m.patch_edge);
    vec2 cell_f = floor(u / l);
    vec2 f = u / l - cell_f;
    ivec2 cell = ivec2(cell_f);
    vec2 local = u - cell_f * l;
    vec2 wx = vec2(1.0 - f.x, f.x);
    vec2 wy = vec2(1.0 - f.y, f.y);
    vec2 dw = vec2(-1.0 / l, 1.0 / l);
    vec2 value[4];
    mat2 jac[4];
    float w[4];
    vec2 grad_w[4];
    for (int i = 0; i < 4; i++) {
        int a = i & 1;
        int b = i >> 1;
        vec2 o = vec2(glint_vertex_origin(m, cell + ivec2(a, b)));
        vec2 shift = vec2(float(1 - a) * l, float(1 - b) * l);
        value[i] = glint_example_sample(m, o + local + shift, jac[i]);
        w[i] = wx[a] * wy[b];
        grad_w[i] = vec2(dw[a] * wy[b], wx[a] * dw[b]);
    }
    GlintPoint r;
    if (m.mode == GLINT_BLEND_NONE) {
        int best = 0;
        for (int i = 1; i < 4; i++) {
            if (w[i] > w[best]) {
                best = i;
            }
        }
        r.normal = value[best];
        r.jacobian = jac[best];
        r.jacobian_exact = jac[best];
        return r;
    }
    float c[4];
    vec2 dc[4];
    if (m.mode == GLINT_BLEND_LINEAR) {
        for (int i = 0; i < 4; i++) {
            c[i] = w[i];
            dc[i] = grad_w[i];
        }
    } else {
        float w2 = 0.0;
        vec2 dw2 = vec2(0.0);
        for (int i = 0; i < 4; i++) {
            w2 += w[i] * w[i];
            dw2 += w[i] * grad_w[i];
        }
        float norm = sqrt(w2);
        vec2 d_norm = dw2 / norm;
        for (int i = 0; i < 4; i++) {
            c[i] = w[i] / norm;
            dc[i] = grad_w[i] / norm - w[i] * d_norm / (norm * norm);
        }
    }
    vec2 rows[2];
    vec2 rows_exact[2];
    for (uint k = 0u; k < 2u; k++) {
        float s = 0.0;
        vec2 grad = vec2(0.0);
        vec2 grad_c = vec2(0.0);
        for (int i = 0; i < 4; i++) {
            float dy;
            float y = glint_normal_to_blend(m, k, value[i][k], dy);
            s += c[i] * y;
            // Row k of the input's Jacobian: (d n_k / dx, d n_k / dy).
            grad += c[i] * dy * vec2(jac[i][0][k], jac[i][1][k]);
            grad_c += y * dc[i];
        }
        float dn;
        r.normal[k] = glint_blend_to_normal(m, k, s, dn);
        rows[k] = dn * grad;
        rows_exact[k] = dn * (grad + grad_c);
    }
    r.jacobian = mat2(vec2(rows[0].x, rows[1].x), vec2(rows[0].y, rows[1].y));
    r.jacobian_exact = mat2(vec2(rows_exact[0].x, rows_exact[1].x), vec2(rows_exact[0].y, rows_exact[1].y));
    return r;
}

#endif
