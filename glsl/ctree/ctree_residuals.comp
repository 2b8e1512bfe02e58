#version 460
// Compressed-tree build, level pc.level, one invocation per lattice node: the residual of the
// field against the primal prediction from the level above (residuals::predict), kept in the
// level's codes until ctree_quantize (the prediction in its values), and its magnitude into the
// level's maximum; 0 for nodes past the samples that code nothing (ctree::Border).
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.count) {
        return;
    }
    uint l = pc.level;
    uvec3 q = ct_coords(l, i);
    int prediction = 0;
    if (l == 1u) {
        prediction = ct_values(0u).v[0];
    } else if (l >= 2u) {
        uvec3 lo = q / 2u;
        uvec3 hi = (q + 1u) / 2u;
        uint odd = 0u;
        for (uint k = 0u; k < pc.dims; ++k) {
            odd += lo[k] != hi[k] ? 1u : 0u;
        }
        int sum = 0;
        for (uint c = 0u; c < (1u << pc.dims); ++c) {
            uvec3 p = uvec3(0u);
            bool skip = false;
            for (uint k = 0u; k < pc.dims; ++k) {
                bool upper = ((c >> k) & 1u) == 1u;
                skip = skip || (upper && lo[k] == hi[k]);
                p[k] = upper ? hi[k] : lo[k];
            }
            if (!skip) {
                sum += ct_values(l - 1u).v[ct_index(l - 1u, p)];
            }
        }
        prediction = sum >> odd;
    }
    ct_values(l).v[i] = prediction;
    // Nodes past the samples (or past the anchors) code nothing (residuals::Residuals::build).
    if (!ct_codes_residual(l, q)) {
        ct_codes(l).v[i] = 0;
        return;
    }
    int t = ct_target(l, q) - prediction;
    ct_codes(l).v[i] = t;
    atomicMax(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_MAX_RESIDUAL)], uint64_t(abs(t)));
}
