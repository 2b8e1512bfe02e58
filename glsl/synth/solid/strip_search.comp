#version 460
// Strip search of the solid candidates: for every pixel of the query image, the S pixels of
// the target image whose strips (N samples, spacing h, along the given image axes) are
// closest in RGB, ranked by (distance, pixel index). Brute force over the target pixels
// first_target .. first_target + target_count, folding into the lists of earlier dispatches
// (llvmpipe stops an invocation's loops after 65535 iterations in all, so the host splits the
// targets).
// CPU reference: compute/src/synth/solid/candidates.rs (search_cpu).
#include "common.glsl"
#include "synth/solid.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t query;      // packed colours of the query image's stack level
    uint64_t target;     // packed colours of the target image's stack level
    uint64_t pixels;     // out: S pixel indices per query pixel
    uint64_t distances;  // out: their strip distances
    uint shift;          // log2 of the exemplar side
    uint query_axis;
    uint target_axis;
    uint strip;          // N (odd)
    uint spacing;
    uint s;
    uint first_target;
    uint target_count;
} pc;

void main() {
    uint p = uint(global_index());
    uint n = 1u << (2u * pc.shift);
    if (p >= n) {
        return;
    }
    int half_n = int(pc.strip / 2u);
    uint q_strip[SOLID_MAX_STRIP];
    for (uint i = 0; i < pc.strip; i++) {
        int t = (int(i) - half_n) * int(pc.spacing);
        q_strip[i] = U32Ptr(pc.query).v[solid_along(p, pc.query_axis, t, pc.shift)];
    }
    uint best_d[SOLID_MAX_S];
    uint best_p[SOLID_MAX_S];
    for (uint k = 0; k < pc.s; k++) {
        best_d[k] = pc.first_target == 0u ? 0xffffffffu : U32Ptr(pc.distances).v[p * pc.s + k];
        best_p[k] = pc.first_target == 0u ? 0xffffffffu : U32Ptr(pc.pixels).v[p * pc.s + k];
    }
    uint worst = best_d[pc.s - 1u];
    for (uint q = pc.first_target; q < pc.first_target + pc.target_count; q++) {
        uint d = 0;
        // Partial sums only grow: stop once the strip cannot enter the list.
        for (uint i = 0; i < pc.strip && d < worst; i++) {
            int t = (int(i) - half_n) * int(pc.spacing);
            d += solid_rgb_distance(q_strip[i],
                U32Ptr(pc.target).v[solid_along(q, pc.target_axis, t, pc.shift)]);
        }
        // Targets come in increasing index order, so an equal distance never displaces an
        // earlier entry: the ranking is (distance, index).
        if (d < worst) {
            uint k = pc.s - 1u;
            while (k > 0u && best_d[k - 1u] > d) {
                best_d[k] = best_d[k - 1u];
                best_p[k] = best_p[k - 1u];
                k--;
            }
            best_d[k] = d;
            best_p[k] = q;
            worst = best_d[pc.s - 1u];
        }
    }
    for (uint k = 0; k < pc.s; k++) {
        U32Ptr(pc.pixels).v[p * pc.s + k] = best_p[k];
        U32Ptr(pc.distances).v[p * pc.s + k] = best_d[k];
    }
}
