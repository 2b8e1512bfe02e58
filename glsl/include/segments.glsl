// Segmented streaming for scan and reduce: invocation t owns the words
// [t * seg_len, (t + 1) * seg_len) of one bound chunk of n words (seg_len is a multiple of 4)
// and walks them in order, four at a time. On lavapipe this beats workgroup-cooperative tiles
// by far: a barrier, shared memory and subgroup operations cost about 6.5 us per workgroup
// there, while a serial uvec4 stream runs at copy speed.
#ifndef LAZYSOLID_SEGMENTS_GLSL
#define LAZYSOLID_SEGMENTS_GLSL

layout(binding = 0, scalar) readonly buffer Src { uvec4 src[]; };

// Quad `q` of the chunk with words at or past `n` replaced by `fill` (bindings are padded to
// whole uvec4, so a partial last quad may be read).
uvec4 load_quad(uint q, uint n, uint fill) {
    uvec4 v = src[q];
    uint w = 4u * q;
    if (w + 4u > n) {
        v.y = w + 1u < n ? v.y : fill;
        v.z = w + 2u < n ? v.z : fill;
        v.w = w + 3u < n ? v.w : fill;
    }
    return v;
}

// Words of the chunk to stream: `n`, or when `n_at` is not 0, as many as the word at n_at
// says past the chunk's first word `first` (at most n): a length the device wrote.
uint segments_n(uint64_t n_at, uint n, uint first) {
    if (n_at == 0ul) {
        return n;
    }
    uint total = U32Ptr(n_at).v[0];
    return total <= first ? 0u : min(total - first, n);
}

#endif
