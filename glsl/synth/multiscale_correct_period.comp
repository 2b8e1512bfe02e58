#version 460
// Multiscale correction subpass: no transfers (all zero), period test; see
// glsl/include/synth/multiscale_correct.glsl.
#define MS_TRANSFERS 0
#define MS_PERIOD 1
#include "synth/multiscale_correct.glsl"
