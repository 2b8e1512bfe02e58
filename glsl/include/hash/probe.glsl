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

// x mod d for 32-bit x without a division (Lemire, Kaser and Kurz 2019): m = ceil(2^64 / d),
// computed on the host (`probe::fastmod_multiplier`). Integer division runs lane by lane on
// CPU drivers and is slow on GPUs; this is three multiplications.
uint fastmod32(uint x, uint64_t m, uint d) {
    uint64_t low = m * uint64_t(x);
    uint64_t t = uint64_t(uint(low)) * uint64_t(d);
    uint64_t t2 = uint64_t(uint(low >> 32)) * uint64_t(d) + (t >> 32);
    return uint(t2 >> 32);
}

// key mod table_size (keys of 2^32 and more take the slow path). A branch, not `?:`: a select
// would compute the 64-bit division for every key.
uint table_mod(uint64_t key, uint table_size, uint64_t m) {
    if (key < (1ul << 32)) {
        return fastmod32(uint(key), m, table_size);
    }
    return uint(key % uint64_t(table_size));
}

// The slot of step `age` (1-based) of `key`; `base` is table_mod(key) for the coherent probe
// (computed once per key), unused for the random one.
uint hash_slot_from(uint64_t key, uint base, uint age, uint probe, uint table_size, uint64_t m) {
    if (probe == HASH_PROBE_COHERENT) {
        if (age == 1u) {
            return base;
        }
        uint s = base + fastmod32(coherent_offset(age), m, table_size);
        return s >= table_size ? s - table_size : s;
    }
    // Multiply-shift range reduction of a 32-bit hash: no division.
    return uint((uint64_t(uint(hash_mix64(key * 16ul + uint64_t(age)) >> 32)) * uint64_t(table_size)) >> 32);
}

uint hash_slot(uint64_t key, uint age, uint probe, uint table_size, uint64_t m) {
    uint base = probe == HASH_PROBE_COHERENT ? table_mod(key, table_size, m) : 0u;
    return hash_slot_from(key, base, age, probe, table_size, m);
}

#endif
