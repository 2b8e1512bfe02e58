#version 460
// Crossbar ranking of one role's candidates: for every pixel p, all S x S triples of p with
// its S strip matches in each other role, scored by the full crossbar error (the two match
// distances plus the distance between the two matches' strips along the axis their roles
// share), the `kept` best by (error, i * S + j). The kept list is a max-heap on (error, key):
// a triple enters when it beats the root (the worst kept), replacing it and sifting down, so
// an insertion costs log2(kept) steps instead of an insertion sort's shift, which kept all the
// SIMD lanes waiting whenever one inserted. One dispatch ranks the rows i = first_row ..
// first_row + rows and folds them into the heap of earlier dispatches, kept in `errors` and
// `keys` (llvmpipe stops an invocation's loops after 65535 iterations in all; the host sizes
// the rows, synth/src/solid/candidates_gpu.rs); the last dispatch sorts the heap and
// writes the triples. CPU reference: synth/src/solid/candidates.rs (triples_cpu).
#include "common.glsl"
#include "synth/solid.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t colours1;    // stack-level colours of the first other role (f1)
    uint64_t colours2;    // ... of the second (f2)
    uint64_t m1_pixels;   // S matches of p in f1
    uint64_t m1_distances;
    uint64_t m2_pixels;   // S matches of p in f2
    uint64_t m2_distances;
    uint64_t triples;     // out: kept x 3 packed coordinates per pixel
    uint64_t errors;      // in/out: kept crossbar errors per pixel
    uint64_t keys;        // in/out: their i * S + j
    uint64_t counts;      // out: valid slots per pixel
    uint shift;
    uint axis1;           // image axis of the f1/f2 shared world axis in f1
    uint axis2;           // ... in f2
    uint strip;
    uint spacing;
    uint s;
    uint kept;
    uint role1;           // f1 (the ranked role e is the third)
    uint role2;           // f2
    uint first_row;       // first i this dispatch ranks
    uint rows;            // rows it ranks
} pc;

uint best_e[SOLID_KEPT];
uint best_k[SOLID_KEPT];

// (e, k) ranks after (f, l).
bool after(uint e, uint k, uint f, uint l) {
    return e > f || (e == f && k > l);
}

// Sifts the entry at `at` down the max-heap of the first `size` entries.
void sift_down(uint at, uint size) {
    uint e = best_e[at];
    uint k = best_k[at];
    while (true) {
        uint child = 2u * at + 1u;
        if (child >= size) {
            break;
        }
        if (child + 1u < size && after(best_e[child + 1u], best_k[child + 1u], best_e[child], best_k[child])) {
            child++;
        }
        if (!after(best_e[child], best_k[child], e, k)) {
            break;
        }
        best_e[at] = best_e[child];
        best_k[at] = best_k[child];
        at = child;
    }
    best_e[at] = e;
    best_k[at] = k;
}

void main() {
    uint p = uint(global_index());
    uint n = 1u << (2u * pc.shift);
    if (p >= n) {
        return;
    }
    int half_n = int(pc.strip / 2u);
    // Empty slots are (max, max): all equal, so the first dispatch starts from a valid heap.
    for (uint k = 0; k < pc.kept; k++) {
        uint slot = p * pc.kept + k;
        best_e[k] = pc.first_row == 0u ? 0xffffffffu : U32Ptr(pc.errors).v[slot];
        best_k[k] = pc.first_row == 0u ? 0xffffffffu : U32Ptr(pc.keys).v[slot];
    }
    uint worst = best_e[0];
    uint last_row = min(pc.first_row + pc.rows, pc.s);
    for (uint i = pc.first_row; i < last_row; i++) {
        uint q1 = U32Ptr(pc.m1_pixels).v[p * pc.s + i];
        uint d1 = U32Ptr(pc.m1_distances).v[p * pc.s + i];
        uint strip1[SOLID_MAX_STRIP];
        for (uint t = 0; t < pc.strip; t++) {
            int o = (int(t) - half_n) * int(pc.spacing);
            strip1[t] = U32Ptr(pc.colours1).v[solid_along(q1, pc.axis1, o, pc.shift)];
        }
        for (uint j = 0; j < pc.s; j++) {
            uint q2 = U32Ptr(pc.m2_pixels).v[p * pc.s + j];
            uint e = d1 + U32Ptr(pc.m2_distances).v[p * pc.s + j];
            // Partial sums only grow: stop once the triple cannot enter the list.
            for (uint t = 0; t < pc.strip && e < worst; t++) {
                int o = (int(t) - half_n) * int(pc.spacing);
                e += solid_rgb_distance(strip1[t],
                    U32Ptr(pc.colours2).v[solid_along(q2, pc.axis2, o, pc.shift)]);
            }
            // Keys come in increasing order, so an equal error never displaces an earlier
            // entry: the ranking is (error, key).
            if (e < worst) {
                best_e[0] = e;
                best_k[0] = i * pc.s + j;
                sift_down(0u, pc.kept);
                worst = best_e[0];
            }
        }
    }
    if (last_row < pc.s) {
        for (uint k = 0; k < pc.kept; k++) {
            uint slot = p * pc.kept + k;
            U32Ptr(pc.errors).v[slot] = best_e[k];
            U32Ptr(pc.keys).v[slot] = best_k[k];
        }
        return;
    }
    // Heap sort: the largest goes to the end, leaving the list in increasing (error, key).
    for (uint size = pc.kept; size > 1u; size--) {
        uint e = best_e[0];
        uint k = best_k[0];
        best_e[0] = best_e[size - 1u];
        best_k[0] = best_k[size - 1u];
        best_e[size - 1u] = e;
        best_k[size - 1u] = k;
        sift_down(0u, size - 1u);
    }
    uint role = 3u - pc.role1 - pc.role2;
    for (uint k = 0; k < pc.kept; k++) {
        uint i = best_k[k] / pc.s;
        uint j = best_k[k] - i * pc.s;
        uint t[3];
        t[role] = solid_pack_pixel(p, pc.shift);
        t[pc.role1] = solid_pack_pixel(U32Ptr(pc.m1_pixels).v[p * pc.s + i], pc.shift);
        t[pc.role2] = solid_pack_pixel(U32Ptr(pc.m2_pixels).v[p * pc.s + j], pc.shift);
        uint slot = p * pc.kept + k;
        for (uint r = 0; r < 3; r++) {
            U32Ptr(pc.triples).v[slot * 3u + r] = t[r];
        }
        U32Ptr(pc.errors).v[slot] = best_e[k];
    }
    U32Ptr(pc.counts).v[p] = pc.kept;
}
