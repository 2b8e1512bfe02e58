// One query per invocation: results[i] = the payload of keys[i], or HASH_NOT_FOUND.
#include "common.glsl"
#include "hash/robin_hood_lookup.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t keys;
    uint64_t results;
    uint n;
    uint table_size;
    uint key_bits;
    uint probe;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U32Ptr(pc.results).v[i] = robin_hood_lookup(pc.cells, pc.table_size, pc.fastmod_m, pc.key_bits, pc.probe, U64Ptr(pc.keys).v[i]);
}
