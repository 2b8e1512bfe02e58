// Image textures read at texture coordinates: albedo images and normal maps with their MIP
// pyramids (renderer/src/image_texture). Every step mirrors the CPU twin
// renderer/src/image_texture/sample.rs: wrap, bilinear, trilinear, anisotropic taps.
//
// Bindings (block names, bound by renderer::image_texture::DeviceImages::bindings):
//   ImageRecords  size, levels, encoding and the first texel of each level per image
//   ImageTexels   RGBA8 texels of every level of every image, row 0 at the image's top
//   ImageCtrees   the three compressed trees (Y, Co, Cg) of each IMAGE_ENCODING_CTREE image
#ifndef LAZYSOLID_RENDER_IMAGE_GLSL
#define LAZYSOLID_RENDER_IMAGE_GLSL

#include "ctree/lookup.glsl"

struct ImageRecord {
    uint width;
    uint height;
    uint levels;
    uint encoding;   // IMAGE_ENCODING_*
    uint level_offset[IMAGE_MAX_LEVELS];
    uint normal_filter;  // NORMAL_FILTER_* of a normal map
    uint vmf_record;     // its VmfRecord (render/normal_vmf.glsl) when filtered by vMF
    uint ctree_record;   // its ImageCtree when IMAGE_ENCODING_CTREE
};
struct ImageCtree {
    CtreeParams y;
    CtreeParams co;
    CtreeParams cg;
};
layout(binding = 16, scalar) readonly buffer ImageRecords { ImageRecord image_records[]; };
layout(binding = 17, scalar) readonly buffer ImageTexels { uint image_texels[]; };
layout(binding = 20, scalar) readonly buffer ImageCtrees { ImageCtree image_ctrees[]; };

// 1 when an image of the set is read through compressed trees; 0 compiles image_ctree out.
layout(constant_id = IMAGE_CTREES_ID) const uint IMAGE_CTREES = 1u;

float image_srgb_to_linear(float c) {
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

uvec2 image_level_size(uint img, uint l) {
    return uvec2(max(image_records[img].width >> l, 1u), max(image_records[img].height >> l, 1u));
}

// Texel (x, y) of level l, wrapped, decoded: linear colour and alpha, or the normal's xyz.
vec4 image_fetch(uint img, uint l, int x, int y) {
    uvec2 size = image_level_size(img, l);
    int w = int(size.x);
    int h = int(size.y);
    // GLSL leaves % of a negative operand undefined: wrap through floor division.
    uint xi = uint(x - w * int(floor(float(x) / float(w))));
    uint yi = uint(y - h * int(floor(float(y) / float(h))));
    xi = min(xi, size.x - 1u);
    yi = min(yi, size.y - 1u);
    uint t = image_texels[image_records[img].level_offset[l] + yi * size.x + xi];
    vec4 c = vec4(float(t & 0xffu), float((t >> 8) & 0xffu), float((t >> 16) & 0xffu), float(t >> 24)) / 255.0;
    if (image_records[img].encoding == IMAGE_ENCODING_NORMAL) {
        return vec4(c.xyz * 2.0 - 1.0, 1.0);
    }
    return vec4(image_srgb_to_linear(c.x), image_srgb_to_linear(c.y), image_srgb_to_linear(c.z), c.w);
}

// Bilinear lookup of level l at uv (v up: v = 1 is row 0), repeating.
vec4 image_bilinear(uint img, uint l, vec2 uv) {
    uvec2 size = image_level_size(img, l);
    float x = uv.x * float(size.x) - 0.5;
    float y = (1.0 - uv.y) * float(size.y) - 0.5;
    float x0 = floor(x);
    float y0 = floor(y);
    float fx = x - x0;
    float fy = y - y0;
    int xi = int(x0);
    int yi = int(y0);
    vec4 a = image_fetch(img, l, xi, yi) * (1.0 - fx) + image_fetch(img, l, xi + 1, yi) * fx;
    vec4 b = image_fetch(img, l, xi, yi + 1) * (1.0 - fx) + image_fetch(img, l, xi + 1, yi + 1) * fx;
    return a * (1.0 - fy) + b * fy;
}

// A tree-coded image at uv (v up, repeating) and a fractional level: each YCoCg channel read
// through its tree (primal interpolation, levels blended), rounded, the exact integer inverse
// of YCoCg-R, then sRGB decoded (lazysolid_compute::ctree::colour; CPU twin:
// image_texture/sample.rs, ctree_tap).
vec4 image_ctree(uint img, vec2 uv, float lod) {
    ImageCtree t = image_ctrees[image_records[img].ctree_record];
    vec3 p = vec3(fract(uv.x), 1.0 - fract(uv.y), 0.0);
    // floor(x + 0.5): GLSL leaves round() of halves to the implementation.
    int y = int(floor(ctree_sample(t.y, p, lod) + 0.5));
    int co = int(floor(ctree_sample(t.co, p, lod) + 0.5));
    int cg = int(floor(ctree_sample(t.cg, p, lod) + 0.5));
    int s = y - (cg >> 1);
    int g = cg + s;
    int b = s - (co >> 1);
    int r = b + co;
    vec3 c = vec3(clamp(ivec3(r, g, b), ivec3(0), ivec3(255))) / 255.0;
    return vec4(image_srgb_to_linear(c.x), image_srgb_to_linear(c.y), image_srgb_to_linear(c.z), 1.0);
}

// Trilinear lookup at a fractional level, clamped to the pyramid.
vec4 image_trilinear(uint img, vec2 uv, float lod) {
    if (IMAGE_CTREES != 0u && image_records[img].encoding == IMAGE_ENCODING_CTREE) {
        return image_ctree(img, uv, lod);
    }
    float top = float(image_records[img].levels - 1u);
    lod = clamp(lod, 0.0, top);
    float l0 = floor(lod);
    float f = lod - l0;
    vec4 a = image_bilinear(img, uint(l0), uv);
    if (f > 0.0) {
        a = a * (1.0 - f) + image_bilinear(img, uint(l0) + 1u, uv) * f;
    }
    return a;
}

// The taps of an anisotropic lookup over a footprint with axes a and b (texture-coordinate
// units): the long axis they are spread along, their count n (at most IMAGE_MAX_ANISOTROPY)
// and the level, that of the short axis or of the long one over the taps if larger
// (image_texture/sample.rs, footprint_taps).
void image_footprint_taps(uint img, vec2 a, vec2 b, out vec2 axis, out float n, out float lod) {
    vec2 size = vec2(float(image_records[img].width), float(image_records[img].height));
    float la = length(a * size);
    float lb = length(b * size);
    float major = la >= lb ? la : lb;
    float minor = la >= lb ? lb : la;
    axis = la >= lb ? a : b;
    n = clamp(ceil(major / max(minor, 1e-6)), 1.0, float(IMAGE_MAX_ANISOTROPY));
    lod = log2(max(max(major / n, minor), 1e-6));
}

// The filtered value over a footprint with axes a and b (texture-coordinate units) centred at
// uv: up to IMAGE_MAX_ANISOTROPY trilinear taps along the long axis, at the level of the short
// axis (or of the long one over the taps, if larger).
vec4 image_lookup(uint img, vec2 uv, vec2 a, vec2 b) {
    vec2 axis;
    float n;
    float lod;
    image_footprint_taps(img, a, b, axis, n, lod);
    uint taps = uint(n);
    vec4 sum = vec4(0.0);
    for (uint k = 0u; k < taps; k++) {
        float t = (float(k) + 0.5) / n - 0.5;
        sum += image_trilinear(img, uv + axis * t, lod);
    }
    return sum / n;
}

#endif
