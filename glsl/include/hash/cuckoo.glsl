// Cuckoo hashing in one table with CUCKOO_FUNCTIONS hash functions (Alcantara et al., single
// pass): h_j(k) = ((a_j k + b_j) mod CUCKOO_PRIME) mod |H|. Cells are 64-bit
// [payload : 32 | key + 1 : 32]; 0 is empty. Must match compute/src/hash/cuckoo.rs.
#ifndef LAZYSOLID_HASH_CUCKOO_GLSL
#define LAZYSOLID_HASH_CUCKOO_GLSL

#extension GL_EXT_shader_atomic_int64 : require

uint cuckoo_slot(uint key, uint j, uvec4 a, uvec4 b, uint table_size) {
    return uint((uint64_t(a[j]) * uint64_t(key) + uint64_t(b[j])) % uint64_t(CUCKOO_PRIME)) % table_size;
}

// The payload of `key`, or HASH_NOT_FOUND: at most CUCKOO_FUNCTIONS probes.
uint cuckoo_lookup(uint64_t cells_address, uint table_size, uvec4 a, uvec4 b, uint key) {
    U64Ptr cells = U64Ptr(cells_address);
    for (uint j = 0u; j < CUCKOO_FUNCTIONS; ++j) {
        uint64_t c = cells.v[cuckoo_slot(key, j, a, b, table_size)];
        if (uint(c) == key + 1u) {
            return uint(c >> 32);
        }
    }
    return HASH_NOT_FOUND;
}

#endif
