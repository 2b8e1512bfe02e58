#version 460
// Multiscale correction subpass: transfers read and composed, period test; see
// glsl/include/synth/multiscale_correct.glsl.
#define MS_TRANSFERS 1
#define MS_PERIOD 1
#include "synth/multiscale_correct.glsl"
