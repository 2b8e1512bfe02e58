// Perfect spatial hash lookup (compute/src/hash/perfect), usable from any kernel:
//     #include "common.glsl"
//     #include "hash/perfect.glsl"
//     PerfectHashParams p = <from your push constants or a buffer>;
//     uint v = perfect_lookup(p, point);          // constrained: defined points only
//     uint v; bool hit = perfect_find(p, point, v); // unconstrained: absent points rejected
// h(p) = (p mod |H| + Φ[p mod |Φ|]) mod |H| per axis: one read of the packed offset entry
// (its three words are adjacent) and one read of the payload. The struct is 56 bytes in scalar
// layout; fill it with the bytes of the Rust `PerfectParams` (same field order):
//     struct PerfectHashParams {
//         uint64_t offsets;      // packed Φ: entry q at bit q·d·C, components x, y, z of C bits
//         uint64_t data;         // payload words, block_words per slot
//         uint64_t tags;         // 1 + h1(p) of each slot's key (0: empty); 0 when constrained
//         uint h;                // |H|
//         uint phi;              // |Φ|
//         uint dimensions;       // 2 or 3
//         uint component_bits;   // C: 8 or 16
//         uint dims_x, dims_y, dims_z;  // the universe (for the bounds check of perfect_find)
//         uint block_words;      // payload words per slot (1, or (b+1)^3 for blocked tables)
//     };
#ifndef LAZYSOLID_HASH_PERFECT_GLSL
#define LAZYSOLID_HASH_PERFECT_GLSL

struct PerfectHashParams {
    uint64_t offsets;
    uint64_t data;
    uint64_t tags;
    uint h;
    uint phi;
    uint dimensions;
    uint component_bits;
    uint dims_x;
    uint dims_y;
    uint dims_z;
    uint block_words;
};

// Φ[q] as an offset vector (z = 0 in 2D).
uvec3 perfect_offset(PerfectHashParams p, uint q) {
    uint entry_bits = p.dimensions * p.component_bits;
    uint64_t bit = uint64_t(q) * uint64_t(entry_bits);
    uint w = uint(bit >> 5);
    uint s = uint(bit & 31ul);
    U32Ptr words = U32Ptr(p.offsets);
    uint64_t v = (uint64_t(words.v[w]) | (uint64_t(words.v[w + 1u]) << 32)) >> s;
    if (s + entry_bits > 64u) {
        v |= uint64_t(words.v[w + 2u]) << (64u - s);
    }
    uint c = p.component_bits;
    uint mask = (1u << c) - 1u;
    uint z = p.dimensions == 3u ? uint(v >> (2u * c)) & mask : 0u;
    return uvec3(uint(v) & mask, uint(v >> c) & mask, z);
}

// h1(p) as a linear index into Φ.
uint perfect_bucket(PerfectHashParams p, uvec3 pt) {
    uvec3 m = pt % p.phi;
    return m.x + p.phi * (m.y + p.phi * m.z);
}

// The linear slot of pt.
uint perfect_slot(PerfectHashParams p, uvec3 pt) {
    if (p.dimensions == 2u) {
        pt.z = 0u;
    }
    uvec3 s = (pt % p.h + perfect_offset(p, perfect_bucket(p, pt))) % p.h;
    return s.x + p.h * (s.y + p.h * s.z);
}

// Constrained access: the payload stored for pt (pt must be a key).
uint perfect_lookup(PerfectHashParams p, uvec3 pt) {
    return U32Ptr(p.data).v[perfect_slot(p, pt)];
}

// Unconstrained access: true and the payload when pt is a key; false for any other point.
bool perfect_find(PerfectHashParams p, uvec3 pt, out uint payload) {
    payload = 0u;
    if (p.dimensions == 2u) {
        pt.z = 0u;
    }
    if (any(greaterThanEqual(pt, uvec3(p.dims_x, p.dims_y, p.dims_z)))) {
        return false;
    }
    uint s = perfect_slot(p, pt);
    if (p.tags != 0ul && U32Ptr(p.tags).v[s] != perfect_bucket(p, pt) + 1u) {
        return false;
    }
    payload = U32Ptr(p.data).v[s];
    return true;
}

#endif
