// Integer helpers of the texture synthesizer, mirrored exactly by synth/src/
// (coords.rs, jitter.rs, appearance.rs): every value here is an integer, so the CPU reference
// and any GPU agree bit for bit.
#ifndef LAZYSOLID_SYNTH_GLSL
#define LAZYSOLID_SYNTH_GLSL

// Packed exemplar coordinate: x in the low, y in the high 16 bits.
uvec2 synth_unpack(uint c) {
    return uvec2(c & 0xffffu, c >> 16);
}

uint synth_pack(uvec2 c) {
    return c.x | (c.y << 16);
}

// (c + d) mod n for c in 0..n and |d| <= n (the spacing and the jitter never exceed the
// exemplar side). A compare-and-add each way instead of an integer division, which CPU
// drivers such as llvmpipe scalarize (x86 has no vector integer division).
uint synth_wrap(uint c, int d, uint n) {
    int v = int(c) + d;
    v += v < 0 ? int(n) : 0;
    v -= v >= int(n) ? int(n) : 0;
    return uint(v);
}

uint synth_mix(uint h) {
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

uint synth_hash4(uint a, uint b, uint c, uint d) {
    uint h = synth_mix(a ^ 0x9e3779b9u);
    h = synth_mix(h ^ b);
    h = synth_mix(h ^ c);
    return synth_mix(h ^ d);
}

// floor(spacing * H * r + 1/2) with H in [-1, 1) from the hash and r = strength / 256.
ivec2 synth_jitter(ivec2 p, uint level, uint seed, uint spacing, uint strength) {
    ivec2 j;
    for (uint axis = 0; axis < 2; axis++) {
        uint h = synth_hash4(uint(p.x), uint(p.y), level | (axis << 8), seed);
        int64_t v = int64_t(h >> 16) - 32768;
        j[axis] = int((int64_t(spacing) * v * int64_t(strength) + (int64_t(1) << 22)) >> 23);
    }
    return j;
}

// Appearance vectors are 8 x i8, two words; the 4-diagonal records 8 words (16-byte aligned).
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer UVec2Ptr { uvec2 v[]; };

// The 4 signed bytes of a word, the first in the low byte (synth/src/neighbourhood.rs,
// pack_i8_words).
ivec4 synth_i8x4(uint w) {
    int v = int(w);
    return ivec4(bitfieldExtract(v, 0, 8), bitfieldExtract(v, 8, 8), bitfieldExtract(v, 16, 8),
                 bitfieldExtract(v, 24, 8));
}

#endif
