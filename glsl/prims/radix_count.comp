#version 460
// Radix sort, step 1 of a pass: invocation t owns the contiguous segment
// [t * seg_len, (t + 1) * seg_len) of the keys and counts its digits into its own column of the
// digit-major histogram hist[digit * threads + t]. No atomics: every counter has one writer.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys;
    uint64_t hist;
    uint n;
    uint seg_len;
    uint threads;
    uint shift;
    uint digit_mask;
    uint key64;
} pc;

void main() {
    uint t = uint(global_index());
    if (t >= pc.threads) {
        return;
    }
    U32Ptr hist = U32Ptr(pc.hist);
    for (uint d = 0; d < RADIX_BUCKETS; ++d) {
        hist.v[d * pc.threads + t] = 0u;
    }
    uint begin = min(t * pc.seg_len, pc.n);
    uint end = min(begin + pc.seg_len, pc.n);
    if (pc.key64 != 0) {
        U64Ptr keys = U64Ptr(pc.keys);
        for (uint i = begin; i < end; ++i) {
            uint d = uint(keys.v[i] >> pc.shift) & pc.digit_mask;
            hist.v[d * pc.threads + t] += 1u;
        }
    } else {
        U32Ptr keys = U32Ptr(pc.keys);
        for (uint i = begin; i < end; ++i) {
            uint d = (keys.v[i] >> pc.shift) & pc.digit_mask;
            hist.v[d * pc.threads + t] += 1u;
        }
    }
}
