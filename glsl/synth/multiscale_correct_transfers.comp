#version 460
// Multiscale correction subpass: transfers read and composed, no period test; see
// glsl/include/synth/multiscale_correct.glsl.
#define MS_TRANSFERS 1
#define MS_PERIOD 0
#include "synth/multiscale_correct.glsl"
