#version 460
// Exclusive prefix sum (wrapping u32) of each invocation's segment of `Src` (one bound chunk of
// n words) into `Dst`, starting from the segment's carry carries[first_segment + t] when
// has_carries is 1. Src and Dst may be the same range. When write_total is 1, the chunk's last
// segment writes the grand total to total[0]. `DstWords` is the same range as `Dst`, for the
// last partial quad, whose words past n belong to someone else. When n_at is not 0, the words
// to scan are as many as the word at n_at says (at most the chunk's n; for a length known only
// on the device, one chunk only), and a scan of none still writes its total, 0.
#include "common.glsl"
#include "segments.glsl"

layout(binding = 1, scalar) writeonly buffer Dst { uvec4 dst[]; };
layout(binding = 2, scalar) writeonly buffer DstWords { uint dst_words[]; };
layout(binding = 3, scalar) readonly buffer Carries { uint carries[]; };
layout(binding = 4, scalar) writeonly buffer Total { uint total[]; };
layout(push_constant, scalar) uniform Push {
    uint64_t n_at;
    uint n;
    uint seg_len;
    uint first_segment;
    uint has_carries;
    uint write_total;
} pc;

void main() {
    uint t = uint(global_index());
    uint n = segments_n(pc.n_at, pc.n, pc.first_segment * pc.seg_len);
    uint begin = t * pc.seg_len;
    if (n == 0u && t == 0u && pc.write_total != 0) {
        total[0] = 0u;
    }
    if (begin >= n) {
        return;
    }
    uint end = min(begin + pc.seg_len, n);
    uint running = pc.has_carries != 0 ? carries[pc.first_segment + t] : 0u;
    for (uint q = begin / 4u; 4u * q < end; ++q) {
        uvec4 v = load_quad(q, n, 0u);
        uvec4 out_quad;
        out_quad.x = running;
        out_quad.y = out_quad.x + v.x;
        out_quad.z = out_quad.y + v.y;
        out_quad.w = out_quad.z + v.z;
        running = out_quad.w + v.w;
        if (4u * q + 4u <= n) {
            dst[q] = out_quad;
        } else {
            for (uint c = 0; 4u * q + c < n; ++c) {
                dst_words[4u * q + c] = out_quad[c];
            }
        }
    }
    if (pc.write_total != 0 && end == n) {
        total[0] = running;
    }
}
