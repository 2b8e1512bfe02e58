#version 460
// Cuckoo insertion, one invocation per key: swap the entry into its slot; an evicted entry
// moves to the slot of its next hash function, up to max_iterations swaps. counters[0]: keys
// left unplaced (the build is redone with new hash constants); counters[1]: duplicates met.
#include "common.glsl"
#include "hash/cuckoo.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t keys;
    uint64_t payloads;
    uint64_t counters;
    uvec4 a;
    uvec4 b;
    uint n;
    uint table_size;
    uint max_iterations;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    U64Ptr cells = U64Ptr(pc.cells);
    U32Ptr counters = U32Ptr(pc.counters);
    uint key = uint(U64Ptr(pc.keys).v[i]);
    uint64_t entry = (uint64_t(U32Ptr(pc.payloads).v[i]) << 32) | uint64_t(key + 1u);
    uint slot = cuckoo_slot(key, 0u, pc.a, pc.b, pc.table_size);
    for (uint it = 0u; it < pc.max_iterations; ++it) {
        uint64_t prev = atomicExchange(cells.v[slot], entry);
        if (prev == 0ul) {
            return;
        }
        if (uint(prev) == uint(entry)) {
            atomicAdd(counters.v[1], 1u);
            return;
        }
        entry = prev;
        key = uint(entry) - 1u;
        // Move the evicted entry to the slot of the function after the one that placed it.
        uint next = 0u;
        for (uint j = 0u; j < CUCKOO_FUNCTIONS; ++j) {
            if (cuckoo_slot(key, j, pc.a, pc.b, pc.table_size) == slot) {
                next = (j + 1u) % CUCKOO_FUNCTIONS;
                break;
            }
        }
        slot = cuckoo_slot(key, next, pc.a, pc.b, pc.table_size);
    }
    atomicAdd(counters.v[0], 1u);
}
