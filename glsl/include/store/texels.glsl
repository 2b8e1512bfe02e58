// What every store lookup shares: the voxel of a nearest lookup, the footprint of a trilinear
// one, and the RGBA8 unpacking. Must match compute/src/store/lookup_cpu.rs.
//   nearest:   voxel floor(pos * R), clamped onto the grid;
//   trilinear: samples at voxel centres; q = pos * R - 0.5, corners floor(q) + {0,1}^3 clamped
//              onto the grid (clamp to edge), weights from fract(q);
//   absent texels read as vec4(0): alpha < 1 means (part of) the footprint was not stored;
//   sample:    the trilinear sum, plus the weight of the stored corners (coverage, which a
//              store whose alpha byte carries a relief channel cannot read from alpha) and
//              the gradient of the alpha channel with respect to pos (what relief bends the
//              shading normal by), analytic over the same footprint.
#ifndef LAZYSOLID_STORE_TEXELS_GLSL
#define LAZYSOLID_STORE_TEXELS_GLSL

vec4 store_unpack(uint rgba) {
    return unpackUnorm4x8(rgba);
}

uvec3 store_nearest_voxel(vec3 pos, uint resolution) {
    precise vec3 g = pos * float(resolution);
    return uvec3(clamp(floor(g), vec3(0.0), vec3(float(resolution) - 1.0)));
}

// Base corner and fractions of a trilinear lookup.
void store_trilinear_footprint(vec3 pos, uint resolution, out ivec3 base, out vec3 f) {
    precise vec3 q = pos * float(resolution) - 0.5;
    vec3 b = floor(q);
    f = q - b;
    base = ivec3(b);
}

// Corner o (bit 0: +x, bit 1: +y, bit 2: +z) of the footprint, clamped onto the grid.
uvec3 store_corner(ivec3 base, int o, uint resolution) {
    ivec3 c = base + ivec3(o & 1, (o >> 1) & 1, o >> 2);
    return uvec3(clamp(c, ivec3(0), ivec3(int(resolution) - 1)));
}

float store_corner_weight(vec3 f, int o) {
    vec3 w = mix(1.0 - f, f, vec3(ivec3(o & 1, (o >> 1) & 1, o >> 2)));
    return w.x * w.y * w.z;
}

// What a sample lookup returns (StoreSample in compute/src/store/lookup_cpu.rs).
struct StoreSample {
    vec4 sum;        // the weighted sum the colour lookups return
    float coverage;  // total weight of the stored corners (alpha byte > 0)
    vec3 gradient;   // d(sum.a) / d(pos)
};

StoreSample store_sample_empty() {
    return StoreSample(vec4(0.0), 0.0, vec3(0.0));
}

// Adds a corner read as `texel` with weight w and weight gradient dw.
void store_sample_add(inout StoreSample s, uint texel, float w, vec3 dw) {
    vec4 c = store_unpack(texel);
    s.sum += w * c;
    s.coverage += (texel >> 24) != 0u ? w : 0.0;
    s.gradient += dw * c.a;
}

// Gradient of corner o's weight with respect to pos (q = pos * R - 0.5, so dq/dpos = R).
vec3 store_corner_weight_gradient(vec3 f, int o, uint resolution) {
    vec3 d = vec3(ivec3(o & 1, (o >> 1) & 1, o >> 2));
    vec3 w = mix(1.0 - f, f, d);
    vec3 s = (2.0 * d - 1.0) * float(resolution);
    return vec3(s.x * w.y * w.z, w.x * s.y * w.z, w.x * w.y * s.z);
}

#endif
