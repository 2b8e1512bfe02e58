#version 460
// Compressed-tree build, level pc.level, one invocation per lattice node: the level's step (the
// user's, raised until the largest residual fits CTREE_MAX_CODE codes), the node's code
// (rounded to nearest, halves away from zero) and its reconstructed value.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.count) {
        return;
    }
    uint l = pc.level;
    int max_abs = int(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_MAX_RESIDUAL)]);
    int s = max(int(pc.step), (max_abs + int(CTREE_MAX_CODE) - 1) / int(CTREE_MAX_CODE));
    if (i == 0u) {
        U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_STEP)] = uint64_t(s);
    }
    int t = ct_codes(l).v[i];
    int code = t >= 0 ? (2 * t + s) / (2 * s) : -((-2 * t + s) / (2 * s));
    ct_values(l).v[i] += code * s;
    ct_codes(l).v[i] = code;
}
