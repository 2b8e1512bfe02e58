// 3D Morton keys (x in bit 0) of points with up to 21 bits per axis; must match
// compute/src/hash/keys.rs (morton_encode / morton_decode with 3 dimensions).
#ifndef LAZYSOLID_MORTON_GLSL
#define LAZYSOLID_MORTON_GLSL

uint64_t morton_spread3(uint v) {
    uint64_t x = uint64_t(v) & 0x1ffffful;
    x = (x | (x << 32)) & 0x1f00000000fffful;
    x = (x | (x << 16)) & 0x1f0000ff0000fful;
    x = (x | (x << 8)) & 0x100f00f00f00f00ful;
    x = (x | (x << 4)) & 0x10c30c30c30c30c3ul;
    x = (x | (x << 2)) & 0x1249249249249249ul;
    return x;
}

uint morton_compact3(uint64_t m) {
    uint64_t x = m & 0x1249249249249249ul;
    x = (x | (x >> 2)) & 0x10c30c30c30c30c3ul;
    x = (x | (x >> 4)) & 0x100f00f00f00f00ful;
    x = (x | (x >> 8)) & 0x1f0000ff0000fful;
    x = (x | (x >> 16)) & 0x1f00000000fffful;
    x = (x | (x >> 32)) & 0x1ffffful;
    return uint(x);
}

uint64_t morton3(uvec3 p) {
    return morton_spread3(p.x) | (morton_spread3(p.y) << 1) | (morton_spread3(p.z) << 2);
}

uvec3 morton3_decode(uint64_t m) {
    return uvec3(morton_compact3(m), morton_compact3(m >> 1), morton_compact3(m >> 2));
}

#endif
