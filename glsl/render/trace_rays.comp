#version 460
// Closest hits of a batch of rays through the two-level CWBVH: the kernel the traversal
// tests compare with obvhs, and the ray-throughput benchmark.
#include "common.glsl"
#include "render/cwbvh.glsl"

struct Ray {
    vec3 origin;
    float tmin;
    vec3 direction;
    float tmax;
};
struct RayHit {
    float t;
    uint instance;
    uint triangle;
    float u;
    float v;
    uint pad0, pad1, pad2;
};
layout(binding = 5, scalar) readonly buffer Rays { Ray rays[]; };
layout(binding = 6, scalar) writeonly buffer Hits { RayHit hits[]; };

layout(push_constant, scalar) uniform Push {
    uint first;
    uint n;
    uint any_hit;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    Ray r = rays[pc.first + i];
    TraceHit h;
    bool found = cwbvh_trace(r.origin, r.direction, r.tmin, r.tmax, pc.any_hit != 0u, h);
    RayHit out_hit;
    out_hit.t = h.t;
    out_hit.instance = h.instance;
    out_hit.triangle = found ? cwbvh_mesh_triangle(h.triangle) : NO_HIT;
    out_hit.u = h.u;
    out_hit.v = h.v;
    out_hit.pad0 = cwbvh_stack_overflowed ? 1u : 0u;
    out_hit.pad1 = 0u;
    out_hit.pad2 = 0u;
    hits[pc.first + i] = out_hit;
}
