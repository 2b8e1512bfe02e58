#version 460
// Strip search of the solid candidates: for every pixel of the query image, the S pixels of
// the target image whose strips (N samples, spacing h, along the given image axes) are
// closest in RGB, ranked by (distance, pixel index). Brute force over the target pixels
// first_target .. first_target + target_count, folding into the lists of earlier dispatches
// (llvmpipe stops an invocation's loops after 65535 iterations in all, so the host splits the
// targets). The list is a max-heap on (distance, index) while searching (an insertion costs
// log2(S) steps, not a shift of the list that keeps every SIMD lane waiting), sorted by the
// last dispatch.
// CPU reference: synth/src/solid/candidates.rs (search_cpu).
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

uint best_d[SOLID_MAX_S];
uint best_p[SOLID_MAX_S];

// (d, p) ranks after (e, q).
bool after(uint d, uint p, uint e, uint q) {
    return d > e || (d == e && p > q);
}

// Sifts the entry at `at` down the max-heap of the first `size` entries.
void sift_down(uint at, uint size) {
    uint d = best_d[at];
    uint p = best_p[at];
    while (true) {
        uint child = 2u * at + 1u;
        if (child >= size) {
            break;
        }
        if (child + 1u < size && after(best_d[child + 1u], best_p[child + 1u], best_d[child], best_p[child])) {
            child++;
        }
        if (!after(best_d[child], best_p[child], d, p)) {
            break;
        }
        best_d[at] = best_d[child];
        best_p[at] = best_p[child];
        at = child;
    }
    best_d[at] = d;
    best_p[at] = p;
}

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
    // Empty slots are (max, max): all equal, so the first dispatch starts from a valid heap.
    for (uint k = 0; k < pc.s; k++) {
        best_d[k] = pc.first_target == 0u ? 0xffffffffu : U32Ptr(pc.distances).v[p * pc.s + k];
        best_p[k] = pc.first_target == 0u ? 0xffffffffu : U32Ptr(pc.pixels).v[p * pc.s + k];
    }
    uint worst = best_d[0];
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
            best_d[0] = d;
            best_p[0] = q;
            sift_down(0u, pc.s);
            worst = best_d[0];
        }
    }
    // The last dispatch sorts the heap: the largest goes to the end.
    if (pc.first_target + pc.target_count >= n) {
        for (uint size = pc.s; size > 1u; size--) {
            uint d = best_d[0];
            uint q = best_p[0];
            best_d[0] = best_d[size - 1u];
            best_p[0] = best_p[size - 1u];
            best_d[size - 1u] = d;
            best_p[size - 1u] = q;
            sift_down(0u, size - 1u);
        }
    }
    for (uint k = 0; k < pc.s; k++) {
        U32Ptr(pc.pixels).v[p * pc.s + k] = best_p[k];
        U32Ptr(pc.distances).v[p * pc.s + k] = best_d[k];
    }
}
