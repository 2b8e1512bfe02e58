#version 460
// Compressed-tree build, level pc.level (finest first), one invocation per node: 1 when a
// child codes a nonzero residual or has a live child itself.
#include "common.glsl"
#include "ctree/build.glsl"

void main() {
    uint i = uint(global_index());
    if (i >= pc.count) {
        return;
    }
    uint l = pc.level;
    uvec3 q = ct_coords(l, i);
    uvec3 open = ct_open(l, q);
    uint internal = 0u;
    for (uint c = 0u; c < (1u << pc.dims); ++c) {
        if (ct_child_exists(open, c)) {
            uint j = ct_index(l + 1u, ct_child(l, q, c));
            if (ct_codes(l + 1u).v[j] != 0 || ct_internal(l + 1u).v[j] != 0u) {
                internal = 1u;
            }
        }
    }
    ct_internal(l).v[i] = internal;
}
