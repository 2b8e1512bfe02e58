// State and analysis layout of the multiscale synthesizer (compute/src/synth/multiscale/gpu.rs),
// mirrored exactly by the CPU reference compute/src/synth/multiscale/cpu.rs.
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

// Per exemplar: width, height, finest level, unused.
// Level field of a magnified pixel.
const uint MS_MAGNIFIED = 0xffu;

uint ms_exemplar(uint meta) { return meta & 0xffu; }
uint ms_level(uint meta) { return (meta >> 8) & 0xffu; }

#endif
