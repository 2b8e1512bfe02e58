#version 460
// M-step of spherical EM for one texel (renderer/src/normal_map/mixture.rs::fit): sums the
// chunks' partial responsibilities in chunk order, sets alpha from the mass, mu and kappa from
// the mean normal r (Banerjee's kappa), and stops the texel once the mean log-likelihood moves
// less than the tolerance.
#include "common.glsl"
#include "render/vmf_em.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t lobes;
    uint64_t partials;
    uint64_t likelihoods;
    uint64_t states;
    uint edge;
    uint chunks;
    uint lobe_count;
    float total;      // normals per texel
    float tolerance;  // absolute change of the mean log-likelihood that stops EM
} pc;

float kappa_from_length(float r) {
    r = clamp(r, 0.0, 1.0);
    if (r >= 1.0) {
        return float(VMF_MAX_KAPPA);
    }
    return min((3.0 * r - r * r * r) / (1.0 - r * r), float(VMF_MAX_KAPPA));
}

void main() {
    uint texel = uint(global_index());
    if (texel >= pc.edge * pc.edge) {
        return;
    }
    EmStates states = EmStates(pc.states);
    EmState state = states.v[texel];
    if (state.done != 0u) {
        return;
    }
    EmPartials partials = EmPartials(pc.partials);
    EmLogLikelihoods likelihoods = EmLogLikelihoods(pc.likelihoods);
    EmLobes lobes = EmLobes(pc.lobes);
    float likelihood = 0.0;
    for (uint c = 0u; c < pc.chunks; c++) {
        likelihood += likelihoods.v[texel * pc.chunks + c];
    }
    for (uint j = 0u; j < pc.lobe_count; j++) {
        vec4 acc = vec4(0.0);
        for (uint c = 0u; c < pc.chunks; c++) {
            acc += partials.v[(texel * pc.chunks + c) * pc.lobe_count + j];
        }
        uint at = texel * pc.lobe_count + j;
        EmLobe l = lobes.v[at];
        if (acc.w <= 0.0) {
            l.alpha = 0.0;
        } else {
            vec3 r = acc.xyz / acc.w;
            float len = length(r);
            l.alpha = acc.w / pc.total;
            l.mu = len > 0.0 ? r / len : l.mu;
            l.kappa = kappa_from_length(len);
        }
        lobes.v[at] = l;
    }
    float mean = likelihood / pc.total;
    state.iterations += 1u;
    if (state.iterations > 1u && abs(mean - state.previous) < pc.tolerance) {
        state.done = 1u;
    }
    if (state.iterations >= VMF_EM_MAX_ITERATIONS) {
        state.done = 1u;
    }
    state.previous = mean;
    states.v[texel] = state;
}
