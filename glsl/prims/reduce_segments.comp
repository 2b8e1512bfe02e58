#version 460
// Reduces each invocation's segment of `Src` (one bound chunk of n words) to one word,
// dst[first_segment + t], with the operator of specialization constant 1 (REDUCE_OP_SUM
// wrapping, REDUCE_OP_MIN, REDUCE_OP_MAX). Reduce repeats this until one word is left; scan
// uses it for the segment totals.
#include "common.glsl"
#include "segments.glsl"

layout(constant_id = 1) const uint OP = REDUCE_OP_SUM;

layout(binding = 1, scalar) writeonly buffer Dst { uint dst[]; };
layout(push_constant, scalar) uniform Push {
    uint64_t n_at;     // not 0: the words to reduce are as many as this word says (at most n)
    uint n;
    uint seg_len;
    uint first_segment;
} pc;

uint identity() {
    return OP == REDUCE_OP_MIN ? 0xffffffffu : 0u;
}

uvec4 combine(uvec4 a, uvec4 b) {
    if (OP == REDUCE_OP_MIN) return min(a, b);
    if (OP == REDUCE_OP_MAX) return max(a, b);
    return a + b;
}

uint combine1(uint a, uint b) {
    if (OP == REDUCE_OP_MIN) return min(a, b);
    if (OP == REDUCE_OP_MAX) return max(a, b);
    return a + b;
}

void main() {
    uint t = uint(global_index());
    uint n = segments_n(pc.n_at, pc.n, pc.first_segment * pc.seg_len);
    uint begin = t * pc.seg_len;
    if (begin >= n) {
        return;
    }
    uint end = min(begin + pc.seg_len, n);
    uvec4 acc = uvec4(identity());
    for (uint q = begin / 4u; 4u * q < end; ++q) {
        acc = combine(acc, load_quad(q, n, identity()));
    }
    dst[pc.first_segment + t] = combine1(combine1(acc.x, acc.y), combine1(acc.z, acc.w));
}
