#version 460
// Colours of voxels looked up by key: for each query i that is required (required == 0, or
// required[i] != 0), a binary search over the sorted table keys[0..n_keys] (repeats allowed);
// found: dst[i] = colours[j]; not found: need_out[i] = 1 and the query is counted in
// counters (u64) [0] how many, [1] the smallest such key. A query that is not required, or
// not found, gets dst[i] = 0 when zero_missing != 0 and is left alone otherwise. Every
// address but queries may be 0 (not read / not written).
// Reference: colours_by_key_cpu in compute/src/store/colours.rs.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require

layout(push_constant, scalar) uniform Push {
    uint64_t queries;
    uint64_t keys;
    uint64_t colours;
    uint64_t dst;
    uint64_t required;
    uint64_t need_out;
    uint64_t counters;
    uint n;
    uint n_keys;
    uint zero_missing;
} pc;

// The first index of q in the table, or n_keys when it is absent.
uint find_key(uint64_t q) {
    if (pc.n_keys == 0u) {
        return 0u;
    }
    U64Ptr keys = U64Ptr(pc.keys);
    uint lo = 0u;
    uint hi = pc.n_keys;
    while (lo < hi) {
        uint mid = lo + (hi - lo) / 2u;
        if (keys.v[mid] < q) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return lo < pc.n_keys && keys.v[lo] == q ? lo : pc.n_keys;
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    bool required = pc.required == 0ul || U32Ptr(pc.required).v[i] != 0u;
    bool found = false;
    if (required) {
        uint64_t q = U64Ptr(pc.queries).v[i];
        uint j = find_key(q);
        found = j < pc.n_keys;
        if (found) {
            if (pc.dst != 0ul) {
                U32Ptr(pc.dst).v[i] = U32Ptr(pc.colours).v[j];
            }
        } else if (pc.counters != 0ul) {
            U64Ptr counters = U64Ptr(pc.counters);
            atomicAdd(counters.v[0], 1ul);
            atomicMin(counters.v[1], q);
        }
    }
    if (pc.need_out != 0ul) {
        U32Ptr(pc.need_out).v[i] = required && !found ? 1u : 0u;
    }
    if (!found && pc.zero_missing != 0u && pc.dst != 0ul) {
        U32Ptr(pc.dst).v[i] = 0u;
    }
}
