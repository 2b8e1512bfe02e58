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
    float pad1, pad2;
};

#endif
