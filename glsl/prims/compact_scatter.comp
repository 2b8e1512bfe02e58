#version 460
// Stream compaction, step 3: every kept element i goes to dst[offsets[i]], where offsets is the
// exclusive scan of the marks; the value itself, or its index i when `write_indices` is 1.
// Order is preserved.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t values;
    uint64_t flags;
    uint64_t offsets;
    uint64_t dst;
    uint n;
    uint mode;
    uint sentinel;
    uint write_indices;
} pc;

void main() {
    uint64_t i = global_index();
    if (i >= pc.n) {
        return;
    }
    uint k = uint(i);
    uint value = pc.values != 0 ? U32Ptr(pc.values).v[k] : 0u;
    bool keep = pc.mode == COMPACT_BY_FLAGS ? U32Ptr(pc.flags).v[k] != 0u : value != pc.sentinel;
    if (keep) {
        U32Ptr(pc.dst).v[U32Ptr(pc.offsets).v[k]] = pc.write_indices != 0 ? k : value;
    }
}
