// Lookup in a finished Robin Hood table (coherent or random probing), usable from any kernel:
// define CELL_BITS (64 or 32) and include this file. The cell at the key's first probe slot
// holds MAT, the largest age of the keys rooted there: an empty first cell rejects the key at
// once, otherwise at most MAT probes decide.
#ifndef LAZYSOLID_HASH_ROBIN_HOOD_LOOKUP_GLSL
#define LAZYSOLID_HASH_ROBIN_HOOD_LOOKUP_GLSL

#include "hash/robin_hood_cells.glsl"

// The payload of `key`, or HASH_NOT_FOUND.
uint robin_hood_lookup(uint64_t cells_address, uint table_size, uint64_t fastmod_m, uint key_bits, uint probe, uint64_t key) {
    Cells cells = Cells(cells_address);
    uint64_t key1 = key + 1ul;
    uint base = probe == HASH_PROBE_COHERENT ? table_mod(key, table_size, fastmod_m) : 0u;
    uint home = hash_slot_from(key, base, 1u, probe, table_size, fastmod_m);
    uint64_t cell = uint64_t(cells.v[home]);
    if (cell == 0ul) {
        return HASH_NOT_FOUND;
    }
    uint max_age = cell_age(cell, AGE_SHIFT);
    if (max_age >= 1u && cell_key1(cell, key_bits) == key1) {
        return cell_payload(cell, key_bits, AGE_SHIFT);
    }
    for (uint age = 2u; age <= max_age; ++age) {
        uint64_t c = uint64_t(cells.v[hash_lookup_slot(key, base, age, probe, table_size, fastmod_m)]);
        if (cell_key1(c, key_bits) == key1) {
            return cell_payload(c, key_bits, AGE_SHIFT);
        }
    }
    return HASH_NOT_FOUND;
}

#endif
