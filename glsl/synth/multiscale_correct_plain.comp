#version 460
// Multiscale correction subpass: no transfers (all zero), no period test; see
// glsl/include/synth/multiscale_correct.glsl.
#define MS_TRANSFERS 0
#define MS_PERIOD 0
#include "synth/multiscale_correct.glsl"
