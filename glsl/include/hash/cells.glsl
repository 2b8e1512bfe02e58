// Cells of the Robin Hood hash tables (coherent and random probing), as 64-bit words:
//   [ age : 4 | payload : 60 - key_bits | key + 1 : key_bits ]
// 0 is the empty cell (key + 1 is never 0). During a build the age is the probe step at which
// the key sits, in the most significant bits so that one atomicMax makes the older entry win
// (Robin Hood). After the build the age bits of cell p hold MAT[p], the largest age of the keys
// whose probe sequence starts at p. The compact form packs the same fields into 32 bits, age in
// bits 28..31. Must match compute/src/hash/cell.rs.
#ifndef LAZYSOLID_HASH_CELLS_GLSL
#define LAZYSOLID_HASH_CELLS_GLSL

uint64_t cell_pack(uint age, uint64_t key, uint payload, uint key_bits, uint age_shift) {
    return (uint64_t(age) << age_shift) | (uint64_t(payload) << key_bits) | (key + 1ul);
}

uint cell_age(uint64_t cell, uint age_shift) {
    return uint(cell >> age_shift);
}

// key + 1, or 0 for an empty cell.
uint64_t cell_key1(uint64_t cell, uint key_bits) {
    return cell & ((1ul << key_bits) - 1ul);
}

uint cell_payload(uint64_t cell, uint key_bits, uint age_shift) {
    return uint((cell & ((1ul << age_shift) - 1ul)) >> key_bits);
}

uint64_t cell_with_age(uint64_t cell, uint age, uint age_shift) {
    return (cell & ((1ul << age_shift) - 1ul)) | (uint64_t(age) << age_shift);
}

#endif
