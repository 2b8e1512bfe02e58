// The GPU material: one record per scene material, std430/scalar layout, 160 bytes. Must match
// renderer/src/shading/material.rs (GpuMaterial). Kinds are the MATERIAL_* and TEXTURE_*
// constants of compute/src/shader_constants.rs.
#ifndef LAZYSOLID_RENDER_MATERIAL_GLSL
#define LAZYSOLID_RENDER_MATERIAL_GLSL

struct Material {
    vec3 color;        // albedo (lambertian, plastic), eta (conductor), tint (dielectric)
    uint kind;         // MATERIAL_*
    vec3 emission;     // emitted radiance (emissive)
    float roughness;   // GGX alpha = roughness^2
    vec3 k;            // conductor extinction kappa
    float ior;         // dielectric / plastic coat index of refraction
    vec3 tex_color_a;  // solid texture colours
    uint texture_kind; // TEXTURE_*
    vec3 tex_color_b;
    float tex_scale;   // features per unit of object space
    vec4 coat_albedo[PLASTIC_COAT_KNOTS / 4];  // plastic: the coat's reflectance per knot
    float coat_internal;  // plastic: the coat's reflectance to diffuse light from below
    uint glint;        // glint: index of its GlintRecord (GLINT_NONE otherwise)
    uint albedo_image; // TEXTURE_IMAGE: its ImageRecord (IMAGE_NONE otherwise)
    uint normal_image; // the normal map's ImageRecord (IMAGE_NONE without one)
};

// The material and texture kinds a kernel can meet, one bit per MATERIAL_* and TEXTURE_*. The
// path tracer declares them as specialization constants set from the scene, so the kinds a
// scene does not use are compiled out (on a CPU device every masked branch still costs
// registers and compile time; the glint BSDF alone made the path tracer 1.6x slower and its
// pipeline 13 s longer to build on lavapipe). Other kernels keep every kind.
#ifndef MATERIAL_KINDS_SPECIALIZED
const uint MATERIAL_KINDS = 0xffffffffu;
const uint TEXTURE_KINDS = 0xffffffffu;
#endif

bool material_kind_used(uint kind) {
    return (MATERIAL_KINDS & (1u << kind)) != 0u;
}

bool texture_kind_used(uint kind) {
    return (TEXTURE_KINDS & (1u << kind)) != 0u;
}

#endif
