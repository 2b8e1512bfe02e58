#version 460
// Stream compaction, step 3: invocation t writes the kept words of its segment, in order, from
// dst[offsets[first_segment + t]] on (offsets: the exclusive scan of step 1's counts). Each
// writes the value, or its global index first_index + word when write_indices is 1. The output
// is addressed by device address: a kept word may land anywhere in it. Stores are branchless:
// a dropped word is stored to the one-word `trash` buffer instead (on lavapipe a data-dependent
// branch per word costs more than the extra store).
#include "common.glsl"
#include "compact_keep.glsl"

layout(binding = 2, scalar) readonly buffer Offsets { uint offsets[]; };
layout(push_constant, scalar) uniform Push {
    uint64_t dst;
    uint64_t trash;
    uint n;
    uint seg_len;
    uint first_segment;
    uint first_index;
    uint mode;
    uint sentinel;
    uint write_indices;
} pc;

void main() {
    uint t = uint(global_index());
    uint begin = t * pc.seg_len;
    if (begin >= pc.n) {
        return;
    }
    uint end = min(begin + pc.seg_len, pc.n);
    uint64_t pos = pc.dst + 4ul * uint64_t(offsets[pc.first_segment + t]);
    for (uint q = begin / 4u; 4u * q < end; ++q) {
        uvec4 values;
        uvec4 keep = uvec4(kept(q, pc.n, pc.mode, pc.sentinel, values));
        uvec4 out_words = pc.write_indices != 0 ? uvec4(pc.first_index + 4u * q) + uvec4(0u, 1u, 2u, 3u) : values;
        for (uint c = 0; c < 4u; ++c) {
            U32Ptr(keep[c] != 0u ? pos : pc.trash).v[0] = out_words[c];
            pos += 4ul * uint64_t(keep[c]);
        }
    }
}
