#version 460
// 64-bit cells; see glsl/include/hash/robin_hood_insert.glsl.
#define CELL_BITS 64
#include "hash/robin_hood_insert.glsl"
