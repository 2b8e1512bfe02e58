// Shared helpers for every kernel. Include once per kernel, after the #version line.
#ifndef LAZYSOLID_COMMON_GLSL
#define LAZYSOLID_COMMON_GLSL

#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

// Workgroup width: specialization constant 0, set by the host (256 by default).
layout(local_size_x_id = 0) in;

// Linear workgroup index: the host folds large dispatches into a second dimension.
uint group_index() {
    return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
}

// Linear invocation index over the folded dispatch.
uint64_t global_index() {
    return uint64_t(group_index()) * uint64_t(gl_WorkGroupSize.x) + uint64_t(gl_LocalInvocationID.x);
}

// Device-address views of buffers (no 128 MiB binding limit applies to these).
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer U32Ptr { uint v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 16) buffer UVec4Ptr { uvec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 8) buffer U64Ptr { uint64_t v[]; };

#endif
