#version 460
// Radix sort, step 1 of a pass: invocation t owns the contiguous segment
// [t * seg_len, (t + 1) * seg_len) of the keys (n keys, or as many as word n_at holds when
// the count is known only on the device) and counts its digits into its own column of the
// digit-major histogram hist[digit * threads + t]. No atomics: every counter has one writer.
// The counting itself happens in a private array (cheaper than buffer memory on lavapipe).
// u32 keys are read four at a time (seg_len is a multiple of 4): on lavapipe every per-lane
// memory access costs about the same whatever its width.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys;
    uint64_t hist;
    uint64_t n_at;     // not 0: the key count is this word (at most n), read on the device
    uint64_t hist_n;   // with n_at: out, the histogram's length for its scan
    uint n;
    uint seg_len;
    uint threads;
    uint shift;
    uint digit_mask;
    uint key64;
} pc;

void main() {
    uint t = uint(global_index());
    uint n = pc.n;
    uint seg_len = pc.seg_len;
    uint threads = pc.threads;
    if (pc.n_at != 0ul) {
        // A count known on the device: as many invocations as it needs, at most `threads`,
        // each with a segment of the same length (radix_sort.rs, record_u64_counted).
        n = min(U32Ptr(pc.n_at).v[0], pc.n);
        threads = clamp((n + RADIX_KEYS_PER_INVOCATION - 1u) / RADIX_KEYS_PER_INVOCATION, 1u,
                        pc.threads);
        seg_len = ((n + threads - 1u) / threads + 3u) & ~3u;
    }
    if (t >= threads) {
        return;
    }
    U32Ptr hist = U32Ptr(pc.hist);
    uint buckets = pc.digit_mask + 1u;
    uint c[RADIX_BUCKETS];
    for (uint d = 0; d < RADIX_BUCKETS; ++d) {
        c[d] = 0u;
    }
    if (pc.n_at != 0ul && t == 0u) {
        U32Ptr(pc.hist_n).v[0] = RADIX_BUCKETS * threads;
    }
    uint begin = min(t * seg_len, n);
    uint end = min(begin + seg_len, n);
    if (pc.key64 != 0) {
        U64Ptr keys = U64Ptr(pc.keys);
        for (uint i = begin; i < end; ++i) {
            uint d = uint(keys.v[i] >> pc.shift) & pc.digit_mask;
            c[d] += 1u;
        }
    } else {
        uint i = begin;
        UVec4Ptr quads = UVec4Ptr(pc.keys);
        for (; i + 4u <= end; i += 4u) {
            uvec4 d = (quads.v[i / 4u] >> pc.shift) & pc.digit_mask;
            c[d.x] += 1u;
            c[d.y] += 1u;
            c[d.z] += 1u;
            c[d.w] += 1u;
        }
        U32Ptr keys = U32Ptr(pc.keys);
        for (; i < end; ++i) {
            uint d = (keys.v[i] >> pc.shift) & pc.digit_mask;
            c[d] += 1u;
        }
    }
    for (uint d = 0; d < buckets; ++d) {
        hist.v[d * threads + t] = c[d];
    }
}
