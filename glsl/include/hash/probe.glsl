// Probe sequences of the Robin Hood hashes; must match compute/src/hash/probe.rs.
//   coherent: h_a(k) = (k + o_(a-1)) mod |H|: the whole table translated at each step, so
//             neighbouring keys stay neighbours (García et al. 2011);
//   random:   h_a(k) = mix(k, a) mod |H|, a fresh pseudo-random slot at each step.
#ifndef LAZYSOLID_HASH_PROBE_GLSL
#define LAZYSOLID_HASH_PROBE_GLSL

const uint COHERENT_OFFSETS[16] = uint[16](
    COHERENT_OFFSET_0, COHERENT_OFFSET_1, COHERENT_OFFSET_2, COHERENT_OFFSET_3,
    COHERENT_OFFSET_4, COHERENT_OFFSET_5, COHERENT_OFFSET_6, COHERENT_OFFSET_7,
    COHERENT_OFFSET_8, COHERENT_OFFSET_9, COHERENT_OFFSET_10, COHERENT_OFFSET_11,
    COHERENT_OFFSET_12, COHERENT_OFFSET_13, COHERENT_OFFSET_14, COHERENT_OFFSET_15);

// splitmix64's finalizer.
uint64_t hash_mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ul;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebul;
    return z ^ (z >> 31);
}

// Offset of probe step `age` (1-based); past the 16 tabulated offsets (only plain open
// addressing, which has no age limit, goes there) a pseudo-random 24-bit offset.
uint coherent_offset(uint age) {
    return age <= 16u ? COHERENT_OFFSETS[age - 1u] : uint(hash_mix64(uint64_t(age)) >> 40);
}

uint hash_slot(uint64_t key, uint age, uint probe, uint table_size) {
    if (probe == HASH_PROBE_COHERENT) {
        return uint((key + uint64_t(coherent_offset(age))) % uint64_t(table_size));
    }
    return uint(hash_mix64(key * 16ul + uint64_t(age)) % uint64_t(table_size));
}

#endif
