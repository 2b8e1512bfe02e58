// After a build: MAT[p] = the largest age of the keys whose first probe slot is p, and, when
// `histogram` is not 0, the number of keys at each age (the age histogram of Fig. 4.16).
#include "common.glsl"
#include "hash/robin_hood_cells.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t mat;
    uint64_t histogram;
    uint table_size;
    uint key_bits;
    uint probe;
} pc;

void main() {
    uint s = uint(global_index());
    if (s >= pc.table_size) {
        return;
    }
    uint64_t cell = uint64_t(Cells(pc.cells).v[s]);
    if (cell == 0ul) {
        return;
    }
    uint age = cell_age(cell, AGE_SHIFT);
    uint home = hash_slot(cell_key1(cell, pc.key_bits) - 1ul, 1u, pc.probe, pc.table_size, pc.fastmod_m);
    atomicMax(U32Ptr(pc.mat).v[home], age);
    if (pc.histogram != 0ul) {
        atomicAdd(U32Ptr(pc.histogram).v[age], 1u);
    }
}
