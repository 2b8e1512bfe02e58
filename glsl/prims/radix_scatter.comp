#version 460
// Radix sort, step 3 of a pass: after the exclusive scan of the digit-major histogram,
// hist[digit * threads + t] is where invocation t's first key of that digit goes. Walking its
// segment in order keeps the pass stable. Values (u32) move with their keys when `vals_in` is
// not 0.
//
// Cost model (lavapipe): an access to buffer memory at a per-invocation address runs lane by
// lane and dominates the run time; a dynamically indexed private array costs about half as
// much. So the next output position of each digit lives in a private array, and u32 keys are
// read four at a time. (Write-combining the stores through private uvec4 arrays was measured
// 3x slower: dynamic component indexing of private vectors is expensive there.)
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys_in;
    uint64_t keys_out;
    uint64_t vals_in;
    uint64_t vals_out;
    uint64_t hist;
    uint64_t n_at;     // not 0: the key count is this word (at most n), read on the device
    uint n;
    uint seg_len;
    uint threads;
    uint shift;
    uint digit_mask;
    uint key64;
} pc;

uint g_next[RADIX_BUCKETS];

uint claim(uint digit) {
    uint pos = g_next[digit];
    g_next[digit] = pos + 1u;
    return pos;
}

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
    for (uint d = 0; d <= pc.digit_mask; ++d) {
        g_next[d] = hist.v[d * threads + t];
    }
    uint begin = min(t * seg_len, n);
    uint end = min(begin + seg_len, n);
    bool with_values = pc.vals_in != 0;
    U32Ptr vals_in = U32Ptr(pc.vals_in);
    U32Ptr vals_out = U32Ptr(pc.vals_out);
    if (pc.key64 != 0) {
        U64Ptr keys_in = U64Ptr(pc.keys_in);
        U64Ptr keys_out = U64Ptr(pc.keys_out);
        for (uint i = begin; i < end; ++i) {
            uint64_t key = keys_in.v[i];
            uint pos = claim(uint(key >> pc.shift) & pc.digit_mask);
            keys_out.v[pos] = key;
            if (with_values) {
                vals_out.v[pos] = vals_in.v[i];
            }
        }
    } else {
        U32Ptr keys_out = U32Ptr(pc.keys_out);
        UVec4Ptr quads = UVec4Ptr(pc.keys_in);
        UVec4Ptr value_quads = UVec4Ptr(pc.vals_in);
        uint i = begin;
        for (; i + 4u <= end; i += 4u) {
            uvec4 k = quads.v[i / 4u];
            uvec4 d = (k >> pc.shift) & pc.digit_mask;
            uvec4 pos = uvec4(claim(d.x), claim(d.y), claim(d.z), claim(d.w));
            keys_out.v[pos.x] = k.x;
            keys_out.v[pos.y] = k.y;
            keys_out.v[pos.z] = k.z;
            keys_out.v[pos.w] = k.w;
            if (with_values) {
                uvec4 v = value_quads.v[i / 4u];
                vals_out.v[pos.x] = v.x;
                vals_out.v[pos.y] = v.y;
                vals_out.v[pos.z] = v.z;
                vals_out.v[pos.w] = v.w;
            }
        }
        U32Ptr keys_in = U32Ptr(pc.keys_in);
        for (; i < end; ++i) {
            uint key = keys_in.v[i];
            uint pos = claim((key >> pc.shift) & pc.digit_mask);
            keys_out.v[pos] = key;
            if (with_values) {
                vals_out.v[pos] = vals_in.v[i];
            }
        }
    }
}
