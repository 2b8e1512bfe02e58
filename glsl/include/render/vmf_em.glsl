// Shared records of the vMF EM kernels (vmf_em_accumulate.comp, vmf_em_update.comp; the CPU
// twin is renderer/src/normal_map/mixture.rs::fit, the host side normal_map/gpu_fit.rs).
#ifndef LAZYSOLID_RENDER_VMF_EM_GLSL
#define LAZYSOLID_RENDER_VMF_EM_GLSL

// One lobe: mean direction, concentration, weight (scalar layout, 20 bytes).
struct EmLobe {
    vec3 mu;
    float kappa;
    float alpha;
};

// Per texel: the previous iteration's mean log-likelihood, whether EM has stopped, and the
// iterations run.
struct EmState {
    float previous;
    uint done;
    uint iterations;
    float pad;
};

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EmNormals { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EmLobes { EmLobe v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EmPartials { vec4 v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EmLogLikelihoods { float v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer EmStates { EmState v[]; };

#endif
