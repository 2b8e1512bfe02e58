// One query per invocation: results[i] = the payload of keys[i], or HASH_NOT_FOUND.
#include "common.glsl"
#include "hash/robin_hood_lookup.glsl"

// The probe sequence, fixed when the pipeline is built (one pipeline per probe): CPU drivers
// execute both sides of a branch on a push-constant value, so a runtime probe would cost every
// coherent query the random probe's 64-bit mixing as well.
layout(constant_id = 1) const uint PROBE = HASH_PROBE_COHERENT;

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t keys;
    uint64_t results;
    uint n;
    uint table_size;
    uint key_bits;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U32Ptr(pc.results).v[i] = robin_hood_lookup(pc.cells, pc.table_size, pc.fastmod_m, pc.key_bits, PROBE, U64Ptr(pc.keys).v[i]);
}
