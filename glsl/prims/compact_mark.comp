#version 460
// Stream compaction, step 1: marks[i] = 1 where element i is kept, else 0. Kept means
// flags[i] != 0 (COMPACT_BY_FLAGS) or values[i] != sentinel (COMPACT_BY_SENTINEL).
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t values;
    uint64_t flags;
    uint64_t marks;
    uint n;
    uint mode;
    uint sentinel;
} pc;

void main() {
    uint64_t i = global_index();
    if (i >= pc.n) {
        return;
    }
    uint k = uint(i);
    bool keep = pc.mode == COMPACT_BY_FLAGS ? U32Ptr(pc.flags).v[k] != 0u : U32Ptr(pc.values).v[k] != pc.sentinel;
    U32Ptr(pc.marks).v[k] = keep ? 1u : 0u;
}
