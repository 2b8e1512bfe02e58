#version 460
// Stream compaction, step 1: counts[first_segment + t] = the number of kept words in
// invocation t's segment of the bound chunk (`Src` = values, `Flags` = flags; see
// compact_keep.glsl).
#include "common.glsl"
#include "compact_keep.glsl"

layout(binding = 2, scalar) writeonly buffer Counts { uint counts[]; };
layout(push_constant, scalar) uniform Push {
    uint n;
    uint seg_len;
    uint first_segment;
    uint mode;
    uint sentinel;
} pc;

void main() {
    uint t = uint(global_index());
    uint begin = t * pc.seg_len;
    if (begin >= pc.n) {
        return;
    }
    uint end = min(begin + pc.seg_len, pc.n);
    uvec4 count = uvec4(0u);
    for (uint q = begin / 4u; 4u * q < end; ++q) {
        uvec4 values;
        count += uvec4(kept(q, pc.n, pc.mode, pc.sentinel, values));
    }
    counts[pc.first_segment + t] = count.x + count.y + count.z + count.w;
}
