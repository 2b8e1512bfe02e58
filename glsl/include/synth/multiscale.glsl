// State and analysis layout of the multiscale synthesizer (synth/src/multiscale/gpu.rs),
// mirrored exactly by the CPU reference synth/src/multiscale/cpu.rs.
#ifndef LAZYSOLID_MULTISCALE_GLSL
#define LAZYSOLID_MULTISCALE_GLSL

#include "synth/synth.glsl"

// One pixel: packed coordinate, exemplar | level << 8, cumulative colour offset (1/16 levels).
struct MsState {
    uint coord;
    uint meta;
    int tr;
    int tg;
    int tb;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer MsStates { MsState v[]; };

// A pixel's working state during correction (synth/src/multiscale/atlas.rs), in two
// buffers: its texel index in the depth set's packed layout, MS_FIXED set when it is not
// corrected and offers no candidates (magnified: its leaf's finest texel, predicted without
// shift; its stack level absent from the set: the zero texel after the last), and its
// transfer packed by ms_pack_transfer.
// (The MULTISCALE_* values come from compute/src/shader_constants.rs.)
const uint MS_ABSENT = MULTISCALE_ABSENT;
const uint MS_FIXED = MULTISCALE_FIXED;
// Flag of a candidate texel (and of a level's lookup entry) whose level offers candidates that
// can be period-penalized (atlas.rs, OFFERS_PERIOD).
const uint MS_OFFERS_PERIOD = MULTISCALE_OFFERS_PERIOD;

// The control words of a depth's correction (gpu.rs): [0] whether some pixel sits at a level
// offering candidates that can be period-penalized (set, never cleared, by the kernels),
// [1..4] and [4..7] the workgroup counts of the correction without and with the period test,
// [7] how many subpasses ran the period test.
const uint MS_CONTROL_WORDS = MULTISCALE_CONTROL_WORDS;

// Lookup slots per exemplar (atlas.rs, LEVEL_SLOTS).
const uint MS_LEVEL_SLOTS = MULTISCALE_LEVEL_SLOTS;

// Largest cumulative transfer component (cpu.rs, MAX_TRANSFER): every one fits 16 bits.
const int MS_MAX_TRANSFER = int(MULTISCALE_MAX_TRANSFER);

// A transfer as 2 words: r | g << 16, b (16-bit two's complement each).
uvec2 ms_pack_transfer(ivec3 t) {
    return uvec2((uint(t.x) & 0xffffu) | (uint(t.y) << 16), uint(t.z) & 0xffffu);
}

ivec3 ms_unpack_transfer(uvec2 w) {
    return ivec3(bitfieldExtract(int(w.x), 0, 16), bitfieldExtract(int(w.x), 16, 16),
                 bitfieldExtract(int(w.y), 0, 16));
}

// Level field of a magnified pixel.
const uint MS_MAGNIFIED = MULTISCALE_MAGNIFIED;

uint ms_exemplar(uint meta) { return meta & 0xffu; }
uint ms_level(uint meta) { return (meta >> 8) & 0xffu; }

#endif
