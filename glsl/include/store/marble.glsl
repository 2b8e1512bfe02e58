// The procedural marble of compute/src/store/marble.rs, in the same integer arithmetic
// (16.16 fixed point), so a store filled on the GPU holds exactly the CPU's bytes and the
// renderer's marble texture matches its CPU twin.
// int64_t marble_band(i64vec3 num, int64_t den, uint seed): band at the point num / den.
// int64_t marble_band_at(vec3 p, uint seed): band at p given in lattice cells.
// uint marble_rgba8(uvec3 voxel, uint resolution, uint seed): RGBA8, red in the low byte.
#ifndef LAZYSOLID_STORE_MARBLE_GLSL
#define LAZYSOLID_STORE_MARBLE_GLSL

#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

const int64_t MARBLE_BASE_FREQUENCY = 4l;
const int64_t MARBLE_BAND_ONE = 65536l;
const uint MARBLE_OCTAVES = 3u;

uint marble_hash3(uint x, uint y, uint z, uint seed) {
    uint h = seed ^ (x * 0x8da6b343u) ^ (y * 0xd8163841u) ^ (z * 0xcb1ab31fu);
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    return h ^ (h >> 16);
}

int64_t marble_smooth(int64_t f) {
    return (f * f * (3l * 65536l - 2l * f)) >> 32;
}

int64_t marble_lerp(int64_t a, int64_t b, int64_t s) {
    return a + (((b - a) * s) >> 16);
}

// Floor division by a positive d (SPIR-V's signed division truncates toward zero).
int64_t marble_floor_div(int64_t a, int64_t d) {
    int64_t q = a / d;
    return q * d > a ? q - 1l : q;
}

int64_t marble_value_noise(i64vec3 p, uint seed) {
    uvec3 i = uvec3(p >> 16);
    int64_t s[3] = int64_t[3](marble_smooth(p.x & 0xffffl), marble_smooth(p.y & 0xffffl), marble_smooth(p.z & 0xffffl));
    int64_t c[8];
    for (uint o = 0u; o < 8u; ++o) {
        c[o] = int64_t(marble_hash3(i.x + (o & 1u), i.y + ((o >> 1) & 1u), i.z + (o >> 2), seed) >> 16);
    }
    int64_t x00 = marble_lerp(c[0], c[1], s[0]);
    int64_t x10 = marble_lerp(c[2], c[3], s[0]);
    int64_t x01 = marble_lerp(c[4], c[5], s[0]);
    int64_t x11 = marble_lerp(c[6], c[7], s[0]);
    return marble_lerp(marble_lerp(x00, x10, s[1]), marble_lerp(x01, x11, s[1]), s[2]);
}

int64_t marble_band(i64vec3 num, int64_t den, uint seed) {
    int64_t turbulence = 0l;
    for (uint octave = 0u; octave < MARBLE_OCTAVES; ++octave) {
        int64_t f = MARBLE_BASE_FREQUENCY << octave;
        i64vec3 p = i64vec3(marble_floor_div(num.x * f * 65536l, den),
                            marble_floor_div(num.y * f * 65536l, den),
                            marble_floor_div(num.z * f * 65536l, den));
        turbulence += marble_value_noise(p, seed + octave) >> (octave + 1u);
    }
    int64_t stripe = marble_floor_div(num.x * MARBLE_BASE_FREQUENCY * 65536l, den);
    int64_t phase = (stripe + 6l * turbulence) & 0x1ffffl;
    return phase < 65536l ? phase : 131071l - phase;
}

int64_t marble_band_at(vec3 p, uint seed) {
    i64vec3 num = i64vec3(floor(p * 65536.0));
    return marble_band(num, MARBLE_BASE_FREQUENCY * 65536l, seed);
}

uint marble_rgba8(uvec3 voxel, uint resolution, uint seed) {
    int64_t band = marble_band(2l * i64vec3(voxel) + 1l, 2l * int64_t(resolution), seed);
    const int64_t dark[3] = int64_t[3](60l, 40l, 30l);
    const int64_t light[3] = int64_t[3](235l, 225l, 210l);
    uint rgba = 0xff000000u;
    for (int c = 0; c < 3; ++c) {
        rgba |= uint(marble_lerp(dark[c], light[c], band)) << (8 * c);
    }
    return rgba;
}

#endif
