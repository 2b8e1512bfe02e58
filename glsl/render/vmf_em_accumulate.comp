#version 460
// E-step of spherical EM for one chunk of one texel's covered normals (seed 000 Algorithm 7.1
// with the standard alpha-weighted E-step, as renderer/src/normal_map/mixture.rs::fit): the
// responsibilities' mass and weighted normal sum per lobe, and the chunk's log-likelihood.
// Chunks keep every invocation's loop under lavapipe's per-invocation loop budget;
// vmf_em_update.comp sums them in a fixed order and runs the M-step.
#include "common.glsl"
#include "render/vmf_em.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t normals;     // size^2 unit normals of the finest level (xyz)
    uint64_t lobes;       // edge^2 * lobes EmLobe
    uint64_t partials;    // edge^2 * chunks * lobes: (sum of z n, sum of z)
    uint64_t likelihoods; // edge^2 * chunks
    uint64_t states;      // edge^2 EmState
    uint size;            // the map's edge
    uint edge;            // the level's edge
    uint span;            // normals per texel side: size / edge
    uint chunks;          // chunks per texel
    uint lobe_count;      // J
} pc;

// ln(f64::MIN_POSITIVE): what the CPU adds for a normal no lobe reaches.
const float LN_MIN_POSITIVE = -708.3964185;
// ln of f64's smallest subnormal: below it the CPU's weighted densities are all exactly 0.
const float LN_SMALLEST_F64 = -744.4400719;

// ln of the unit-mass vMF density at cosine t (renderer::normal_map::vmf, density_at_cosine):
// kappa / (2 pi (1 - e^{-2 kappa})) e^{kappa (t - 1)}.
float log_density(float kappa, float t) {
    if (kappa < 1e-6) {
        return -log(4.0 * 3.14159265358979);
    }
    return log(kappa / (2.0 * 3.14159265358979 * (1.0 - exp(-2.0 * kappa)))) + kappa * (t - 1.0);
}

void main() {
    uint i = uint(global_index());
    uint texels = pc.edge * pc.edge;
    if (i >= texels * pc.chunks) {
        return;
    }
    uint texel = i / pc.chunks;
    uint chunk = i % pc.chunks;
    if (EmStates(pc.states).v[texel].done != 0u) {
        return;
    }
    EmLobes lobes = EmLobes(pc.lobes);
    vec3 mu[VMF_MAX_LOBES];
    float kappa[VMF_MAX_LOBES];
    float log_alpha[VMF_MAX_LOBES];
    bool live[VMF_MAX_LOBES];
    vec3 sums[VMF_MAX_LOBES];
    float mass[VMF_MAX_LOBES];
    for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
        EmLobe l = lobes.v[texel * pc.lobe_count + min(j, pc.lobe_count - 1u)];
        mu[j] = l.mu;
        kappa[j] = l.kappa;
        live[j] = j < pc.lobe_count && l.alpha > 0.0;
        log_alpha[j] = live[j] ? log(l.alpha) : 0.0;
        sums[j] = vec3(0.0);
        mass[j] = 0.0;
    }
    uint tx = texel % pc.edge;
    uint ty = texel / pc.edge;
    uint covered = pc.span * pc.span;
    uint first = chunk * VMF_EM_CHUNK;
    uint last = min(first + VMF_EM_CHUNK, covered);
    EmNormals normals = EmNormals(pc.normals);
    float likelihood = 0.0;
    for (uint q = first; q < last; q++) {
        uint row = q / pc.span;
        uint col = q % pc.span;
        vec3 n = normals.v[(ty * pc.span + row) * pc.size + tx * pc.span + col].xyz;
        float ld[VMF_MAX_LOBES];
        float top = -3.0e38;
        for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
            ld[j] = live[j] ? log_alpha[j] + log_density(kappa[j], clamp(dot(mu[j], n), -1.0, 1.0)) : -3.0e38;
            top = max(top, ld[j]);
        }
        // Every weighted density under f64's smallest subnormal: the CPU's norm is 0 and the
        // normal goes to the nearest lobe (the last of equal cosines, as Rust's max_by).
        if (top < LN_SMALLEST_F64) {
            uint nearest = 0u;
            float best = -2.0;
            for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
                float c = dot(mu[j], n);
                if (j < pc.lobe_count && c >= best) {
                    best = c;
                    nearest = j;
                }
            }
            for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
                if (j == nearest) {
                    mass[j] += 1.0;
                    sums[j] += n;
                }
            }
            likelihood += LN_MIN_POSITIVE;
            continue;
        }
        float norm = 0.0;
        for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
            ld[j] = live[j] ? exp(ld[j] - top) : 0.0;
            norm += ld[j];
        }
        likelihood += top + log(norm);
        for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
            float z = ld[j] / norm;
            mass[j] += z;
            sums[j] += n * z;
        }
    }
    EmPartials partials = EmPartials(pc.partials);
    for (uint j = 0u; j < VMF_MAX_LOBES; j++) {
        if (j < pc.lobe_count) {
            partials.v[i * pc.lobe_count + j] = vec4(sums[j], mass[j]);
        }
    }
    EmLogLikelihoods(pc.likelihoods).v[i] = likelihood;
}
