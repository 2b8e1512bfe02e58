#version 460
// Queries of a perfect hash through glsl/include/hash/perfect.glsl: results[i] = the payload of
// keys[i]; with `checked` (unconstrained tables) HASH_NOT_FOUND for keys that are not stored
// or lie outside the universe.
#include "common.glsl"
#include "hash/perfect.glsl"
#include "hash/perfect_keys.glsl"

layout(push_constant, scalar) uniform Push {
    PerfectHashParams table;
    uint64_t keys;
    uint64_t results;
    uint64_t key_count;
    uint n;
    uint layout_id;
    uint axis_bits;
    uint checked;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t key = U64Ptr(pc.keys).v[i];
    uvec3 p;
    bool inside = perfect_key_point(key, pc.layout_id, uvec3(pc.table.dims_x, pc.table.dims_y, pc.table.dims_z), pc.table.dimensions, pc.axis_bits, pc.key_count, p);
    uint result;
    if (pc.checked != 0u) {
        uint payload;
        result = inside && perfect_find(pc.table, p, payload) ? payload : HASH_NOT_FOUND;
    } else {
        result = perfect_lookup(pc.table, p);
    }
    U32Ptr(pc.results).v[i] = result;
}
