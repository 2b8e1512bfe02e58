#version 460
// One query per invocation: results[i] = the payload of keys[i], or HASH_NOT_FOUND.
#include "common.glsl"
#include "hash/cuckoo.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t keys;
    uint64_t results;
    uvec4 a;
    uvec4 b;
    uint n;
    uint table_size;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U32Ptr(pc.results).v[i] = cuckoo_lookup(pc.cells, pc.table_size, pc.a, pc.b, uint(U64Ptr(pc.keys).v[i]));
}
