// Integer helpers of solid synthesis, mirrored exactly by synth/src/solid/ (strips.rs,
// candidates.rs). Exemplars are square with a power-of-two side 2^shift; pixels are row-major
// indices, coordinates packed as in synth.glsl.
#ifndef LAZYSOLID_SOLID_GLSL
#define LAZYSOLID_SOLID_GLSL

#include "synth/synth.glsl"

// Pixel p moved by t along image axis `axis` (0 = u, 1 = v) on the torus.
uint solid_along(uint p, uint axis, int t, uint shift) {
    uint mask = (1u << shift) - 1u;
    uint u = p & mask;
    uint v = p >> shift;
    if (axis == 0u) {
        u = uint(int(u) + t) & mask;
    } else {
        v = uint(int(v) + t) & mask;
    }
    return (v << shift) | u;
}

// Squared distance of two colours packed r | g << 8 | b << 16.
uint solid_rgb_distance(uint a, uint b) {
    ivec3 d = ivec3(int(a & 0xffu), int((a >> 8) & 0xffu), int((a >> 16) & 0xffu))
        - ivec3(int(b & 0xffu), int((b >> 8) & 0xffu), int((b >> 16) & 0xffu));
    return uint(d.x * d.x + d.y * d.y + d.z * d.z);
}

// Packed coordinate of pixel index p.
uint solid_pack_pixel(uint p, uint shift) {
    return synth_pack(uvec2(p & ((1u << shift) - 1u), p >> shift));
}

// World offset d seen in the image plane of a role (synth/src/solid/roles.rs):
// E_x images (y, z), E_y (x, z), E_z (x, y).
ivec2 solid_project(uint role, ivec3 d) {
    return role == 0u ? d.yz : (role == 1u ? d.xz : d.xy);
}

// The 3D jitter of synth/src/solid/jitter.rs.
ivec3 solid_jitter(ivec3 p, uint level, uint seed, uint spacing, uint strength) {
    uint base = synth_hash4(uint(p.x), uint(p.y), uint(p.z), seed);
    ivec3 j;
    for (uint axis = 0; axis < 3; axis++) {
        uint h = synth_hash4(base, level | (axis << 8), 0x5011d000u, 0u);
        int64_t v = int64_t(h >> 16) - 32768;
        j[axis] = int((int64_t(spacing) * v * int64_t(strength) + (int64_t(1) << 22)) >> 23);
    }
    return j;
}

// Packed coordinate c moved by d on the side x side torus (|d| <= side).
uint solid_moved(uint c, ivec2 d, uint side) {
    uvec2 e = synth_unpack(c);
    return synth_pack(uvec2(synth_wrap(e.x, d.x, side), synth_wrap(e.y, d.y, side)));
}

#endif
