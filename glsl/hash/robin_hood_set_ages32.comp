#version 460
// 32-bit cells; see glsl/include/hash/robin_hood_set_ages.glsl.
#define CELL_BITS 32
#include "hash/robin_hood_set_ages.glsl"
