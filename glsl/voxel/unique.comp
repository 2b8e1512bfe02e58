#version 460
// Unique of sorted u64 keys, by flags and a scan: element i is the first of its run when
// i == 0 or keys[i] != keys[i - 1].
// write == 0: flags[i] = 1 for a first element, else 0.
// write == 1: flags holds the scanned flags; out[flags[i]] = keys[i] for every first element.
#include "common.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t keys;
    uint64_t flags;
    uint64_t dst;
    uint n;
    uint write;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U64Ptr keys = U64Ptr(pc.keys);
    uint64_t k = keys.v[i];
    bool head = i == 0u || keys.v[i - 1u] != k;
    if (pc.write == 0u) {
        U32Ptr(pc.flags).v[i] = head ? 1u : 0u;
    } else if (head) {
        U64Ptr(pc.dst).v[U32Ptr(pc.flags).v[i]] = k;
    }
}
