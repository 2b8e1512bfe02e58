// The cell array of a Robin Hood table through its device address, for CELL_BITS 64 or 32.
#ifndef LAZYSOLID_HASH_ROBIN_HOOD_CELLS_GLSL
#define LAZYSOLID_HASH_ROBIN_HOOD_CELLS_GLSL

#extension GL_EXT_shader_atomic_int64 : require
#include "hash/cells.glsl"
#include "hash/probe.glsl"

#if CELL_BITS == 64
#define CELL_T uint64_t
#define AGE_SHIFT 60u
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer Cells { uint64_t v[]; };
#elif CELL_BITS == 32
#define CELL_T uint
#define AGE_SHIFT 28u
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Cells { uint v[]; };
#else
#error CELL_BITS must be 32 or 64
#endif

#endif
