#version 460
// Runs the image-texture lookup (render/image.glsl) on a batch of queries so that tests can
// compare it with its CPU twin (renderer/src/image_texture/sample.rs). Each query is three vec2:
// the texture coordinates and the footprint's two axes; each result one vec4.
#include "common.glsl"
#include "render/image.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Queries { vec2 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Results { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t queries;
    uint64_t results;
    uint image;
    uint n;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    Queries q = Queries(pc.queries);
    Results(pc.results).v[i] = image_lookup(pc.image, q.v[3u * i], q.v[3u * i + 1u], q.v[3u * i + 2u]);
}
