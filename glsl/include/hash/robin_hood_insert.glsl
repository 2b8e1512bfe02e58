// Robin Hood insertion, one invocation per key (García et al. 2011). The age sits in the most
// significant bits of the entry, so one atomicMax lets the older entry keep the slot; the
// evicted, younger one goes on probing. Entries are totally ordered, which makes the final
// table the same whatever order the keys arrive in (it is the key-optimal stable matching of
// keys to slots), so the GPU build equals the sequential CPU reference exactly.
// counters[0]: keys that reached HASH_MAX_AGE unplaced (the build must be redone larger);
// counters[1]: duplicate keys met.
#include "common.glsl"
#include "hash/robin_hood_cells.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t keys;
    uint64_t payloads;
    uint64_t counters;
    uint n;
    uint table_size;
    uint key_bits;
    uint probe;
} pc;

// Each step places or ages an entry; chains of evictions end long before this.
const uint MAX_STEPS = 1u << 16;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    Cells cells = Cells(pc.cells);
    U32Ptr counters = U32Ptr(pc.counters);
    uint64_t entry = cell_pack(1u, U64Ptr(pc.keys).v[i], U32Ptr(pc.payloads).v[i], pc.key_bits, AGE_SHIFT);
    for (uint step = 0u; step < MAX_STEPS; ++step) {
        uint64_t key = cell_key1(entry, pc.key_bits) - 1ul;
        uint slot = hash_slot(key, cell_age(entry, AGE_SHIFT), pc.probe, pc.table_size, pc.fastmod_m);
        uint64_t prev = uint64_t(atomicMax(cells.v[slot], CELL_T(entry)));
        if (prev < entry) {
            if (prev == 0ul) {
                return;
            }
            entry = prev;
        } else if (cell_key1(prev, pc.key_bits) == cell_key1(entry, pc.key_bits)) {
            atomicAdd(counters.v[1], 1u);
            return;
        }
        if (cell_age(entry, AGE_SHIFT) >= HASH_MAX_AGE) {
            atomicAdd(counters.v[0], 1u);
            return;
        }
        entry += 1ul << AGE_SHIFT;
    }
    atomicAdd(counters.v[0], 1u);
}
