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

// key mod d for any 64-bit key, exact and without a division (m = ceil(2^64 / d), 0 for d = 1):
// q = floor(key * m / 2^64) is floor(key / d) or one more, because key * m / 2^64 exceeds
// key / d by less than 1; so key - q * d is the remainder, or the remainder minus d, which
// wraps to 2^64 - d or more and is put right by adding d back. No branch: CPU drivers run
// both sides of a divergent branch, so a 64-bit `%` behind `if` would cost every key a
// lane-by-lane division. Must match `table_mod` in compute/src/hash/probe.rs.
uint table_mod(uint64_t key, uint d, uint64_t m) {
    uint64_t k0 = key & 0xfffffffful;
    uint64_t k1 = key >> 32;
    uint64_t m0 = m & 0xfffffffful;
    uint64_t m1 = m >> 32;
    uint64_t p01 = k0 * m1;
    uint64_t p10 = k1 * m0;
    uint64_t mid = ((k0 * m0) >> 32) + (p01 & 0xfffffffful) + (p10 & 0xfffffffful);
    uint64_t q = k1 * m1 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    uint64_t r = key - q * uint64_t(d);
    r = r >= uint64_t(d) ? r + uint64_t(d) : r;
    return d == 1u ? 0u : uint(r);
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

// hash_slot_from for a lookup, whose ages never exceed HASH_MAX_AGE (< 16): the coherent
// offset comes from the table alone, without the pseudo-random fallback of longer sequences
// (a CPU driver would compute that fallback for every probe, as it runs both sides of `?:`).
uint hash_lookup_slot(uint64_t key, uint base, uint age, uint probe, uint table_size, uint64_t m) {
    if (probe == HASH_PROBE_COHERENT) {
        uint s = base + fastmod32(COHERENT_OFFSETS[age - 1u], m, table_size);
        return s >= table_size ? s - table_size : s;
    }
    return hash_slot_from(key, base, age, probe, table_size, m);
}

uint hash_slot(uint64_t key, uint age, uint probe, uint table_size, uint64_t m) {
    uint base = probe == HASH_PROBE_COHERENT ? table_mod(key, table_size, m) : 0u;
    return hash_slot_from(key, base, age, probe, table_size, m);
}

#endif
