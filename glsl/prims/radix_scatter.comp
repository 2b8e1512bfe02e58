#version 460
// Radix sort, step 3 of a pass: after the exclusive scan of the digit-major histogram,
// hist[digit * threads + t] is where invocation t's first key of that digit goes. Walking its
// segment in order keeps the pass stable. Values (u32) move with their keys when `vals_in` is
// not 0.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys_in;
    uint64_t keys_out;
    uint64_t vals_in;
    uint64_t vals_out;
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
    uint begin = min(t * pc.seg_len, pc.n);
    uint end = min(begin + pc.seg_len, pc.n);
    bool with_values = pc.vals_in != 0;
    if (pc.key64 != 0) {
        U64Ptr keys_in = U64Ptr(pc.keys_in);
        U64Ptr keys_out = U64Ptr(pc.keys_out);
        for (uint i = begin; i < end; ++i) {
            uint64_t key = keys_in.v[i];
            uint slot = (uint(key >> pc.shift) & pc.digit_mask) * pc.threads + t;
            uint pos = hist.v[slot];
            hist.v[slot] = pos + 1u;
            keys_out.v[pos] = key;
            if (with_values) {
                U32Ptr(pc.vals_out).v[pos] = U32Ptr(pc.vals_in).v[i];
            }
        }
    } else {
        U32Ptr keys_in = U32Ptr(pc.keys_in);
        U32Ptr keys_out = U32Ptr(pc.keys_out);
        for (uint i = begin; i < end; ++i) {
            uint key = keys_in.v[i];
            uint slot = ((key >> pc.shift) & pc.digit_mask) * pc.threads + t;
            uint pos = hist.v[slot];
            hist.v[slot] = pos + 1u;
            keys_out.v[pos] = key;
            if (with_values) {
                U32Ptr(pc.vals_out).v[pos] = U32Ptr(pc.vals_in).v[i];
            }
        }
    }
}
