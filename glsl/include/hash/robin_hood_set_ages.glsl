// Rewrites the age bits of every occupied cell: with MAT[s] after a build (mode 0), or back
// with the age at which the resident key sits (mode 1), before inserting a further batch.
#include "common.glsl"
#include "hash/robin_hood_cells.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t mat;
    uint table_size;
    uint key_bits;
    uint probe;
    uint mode;
} pc;

void main() {
    uint s = uint(global_index());
    if (s >= pc.table_size) {
        return;
    }
    Cells cells = Cells(pc.cells);
    uint64_t cell = uint64_t(cells.v[s]);
    if (cell == 0ul) {
        return;
    }
    uint age = 0u;
    if (pc.mode == 0u) {
        age = U32Ptr(pc.mat).v[s];
    } else {
        uint64_t key = cell_key1(cell, pc.key_bits) - 1ul;
        for (uint a = 1u; a <= HASH_MAX_AGE; ++a) {
            if (hash_slot(key, a, pc.probe, pc.table_size, pc.fastmod_m) == s) {
                age = a;
                break;
            }
        }
    }
    cells.v[s] = CELL_T(cell_with_age(cell, age, AGE_SHIFT));
}
