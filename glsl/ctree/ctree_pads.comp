#version 460
// Compressed-tree packing, level pc.level, one invocation per (candidate scale, record): the
// record's padding at the candidate scale pc.first_scale + c, added to the candidate's total
// in scratch (uint64_t; plus 1 << CTREE_INFEASIBLE_SHIFT when an offset does not fit 7 bits).
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint64_t t = global_index();
    if (t >= uint64_t(pc.candidates) * uint64_t(pc.records)) {
        return;
    }
    uint c = uint(t / uint64_t(pc.records));
    uint j = uint(t % uint64_t(pc.records));
    uint l = pc.level;
    uint padding;
    bool fits;
    ct_place(l, ct_records(l).v[j], pc.first_scale + c, padding, fits);
    uint64_t add = uint64_t(padding) + (fits ? 0ul : (1ul << CTREE_INFEASIBLE_SHIFT));
    if (add != 0ul) {
        atomicAdd(U64Ptr(pc.scratch).v[c], add);
    }
}
