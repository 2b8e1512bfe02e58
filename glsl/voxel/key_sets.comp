#version 460
// Union and difference of two sorted, distinct u64 key lists a and b, by tagged keys, a sort,
// flags and a scan. Phases (pc.phase):
// 0: tagged[i] = a[i] << 1 for i < na, b[i - na] << 1 | 1 for na <= i < na + nb;
//    (the caller sorts tagged[..n] by key_bits + 1 bits)
// 1: flags[i] = 1 for a kept element of the sorted tagged keys, else 0. Union keeps the first
//    element of each key's run; difference keeps an element of a (tag 0) whose key is not
//    also b's (the next element, b's twin, would follow it);
// 2: flags holds the scanned flags: dst[flags[i]] = tagged[i] >> 1 for every kept element.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t a;
    uint64_t b;
    uint64_t tagged;
    uint64_t flags;
    uint64_t dst;
    uint na;
    uint nb;
    uint phase;
    uint op;
} pc;

bool kept(U64Ptr t, uint i, uint n) {
    uint64_t k = t.v[i];
    if (pc.op == KEY_SET_UNION) {
        return i == 0u || (t.v[i - 1u] >> 1) != (k >> 1);
    }
    return (k & 1ul) == 0ul && (i + 1u == n || (t.v[i + 1u] >> 1) != (k >> 1));
}

void main() {
    uint i = uint(global_index());
    uint n = pc.na + pc.nb;
    if (i >= n) {
        return;
    }
    U64Ptr t = U64Ptr(pc.tagged);
    if (pc.phase == 0u) {
        t.v[i] = i < pc.na ? U64Ptr(pc.a).v[i] << 1 : (U64Ptr(pc.b).v[i - pc.na] << 1) | 1ul;
    } else if (pc.phase == 1u) {
        U32Ptr(pc.flags).v[i] = kept(t, i, n) ? 1u : 0u;
    } else if (kept(t, i, n)) {
        U64Ptr(pc.dst).v[U32Ptr(pc.flags).v[i]] = t.v[i] >> 1;
    }
}
