#version 460
// The plain R8 MIP texture that compressed-tree lookups are compared with (compute/src/ctree/
// mip_texture.rs, its CPU twin): trilinear at (uv, lod), uv over the texels' centres, clamped.
#include "common.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 16) buffer Vec4Ptr { vec4 v[]; };

layout(push_constant, scalar) uniform Push {
    uint64_t texels;   // 4 texels per uint
    uint64_t levels;   // per level: width, height, first texel
    uint64_t points;   // vec4 (u, v, unused, lod)
    uint64_t results;  // float
    uint level_count;
    uint n;
} pc;

float mip_fetch(uint l, int x, int y) {
    U32Ptr levels = U32Ptr(pc.levels);
    uint w = levels.v[3u * l];
    uint h = levels.v[3u * l + 1u];
    uint i = levels.v[3u * l + 2u] + uint(clamp(y, 0, int(h) - 1)) * w + uint(clamp(x, 0, int(w) - 1));
    return float((U32Ptr(pc.texels).v[i >> 2] >> (8u * (i & 3u))) & 0xffu);
}

float mip_bilinear(uint l, vec2 uv) {
    U32Ptr levels = U32Ptr(pc.levels);
    float x = uv.x * float(levels.v[3u * l]) - 0.5;
    float y = uv.y * float(levels.v[3u * l + 1u]) - 0.5;
    float x0 = floor(x);
    float y0 = floor(y);
    float fx = x - x0;
    float fy = y - y0;
    int xi = int(x0);
    int yi = int(y0);
    float a = mip_fetch(l, xi, yi) * (1.0 - fx) + mip_fetch(l, xi + 1, yi) * fx;
    float b = mip_fetch(l, xi, yi + 1) * (1.0 - fx) + mip_fetch(l, xi + 1, yi + 1) * fx;
    return a * (1.0 - fy) + b * fy;
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    vec4 q = Vec4Ptr(pc.points).v[i];
    float lod = clamp(q.w, 0.0, float(pc.level_count - 1u));
    float l0 = floor(lod);
    float f = lod - l0;
    float a = mip_bilinear(uint(l0), q.xy);
    if (f > 0.0) {
        a = a * (1.0 - f) + mip_bilinear(uint(l0) + 1u, q.xy) * f;
    }
    U32Ptr(pc.results).v[i] = floatBitsToUint(a);
}
