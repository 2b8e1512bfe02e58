#version 460
// Exclusive prefix sum (wrapping u32) of each SCAN_TILE-word tile of `src` into `dst`, offset by
// the tile's carry `carries[tile]` when `carries` is not 0. `src` and `dst` may be the same
// buffer. When `total` is not 0, the last tile writes the grand total there.
#include "common.glsl"
#include "scan_tile.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t src;
    uint64_t dst;
    uint64_t carries;
    uint64_t total;
    uint n;
} pc;

shared uint s_subgroup[gl_WorkGroupSize.x];

void main() {
    uint tile = group_index();
    uint base = tile * SCAN_TILE;
    if (base >= pc.n) {
        return;
    }
    uint first = base + gl_LocalInvocationID.x * SCAN_ITEMS_PER_THREAD;
    uint v[SCAN_ITEMS_PER_THREAD];
    load_items(pc.src, first, pc.n, 0u, v);
    uint mine = 0;
    for (uint j = 0; j < SCAN_ITEMS_PER_THREAD; ++j) {
        mine += v[j];
    }
    uint before_in_subgroup = subgroupExclusiveAdd(mine);
    uint subgroup_total = subgroupAdd(mine);
    if (subgroupElect()) {
        s_subgroup[gl_SubgroupID] = subgroup_total;
    }
    barrier();
    uint running = pc.carries != 0 ? U32Ptr(pc.carries).v[tile] : 0u;
    uint tile_total = running;
    for (uint s = 0; s < gl_NumSubgroups; ++s) {
        uint t = s_subgroup[s];
        running += s < gl_SubgroupID ? t : 0u;
        tile_total += t;
    }
    running += before_in_subgroup;
    if (first + SCAN_ITEMS_PER_THREAD <= pc.n) {
        UVec4Ptr p = UVec4Ptr(pc.dst);
        for (uint j = 0; j < SCAN_VEC4_PER_THREAD; ++j) {
            uvec4 q;
            q.x = running; running += v[4 * j + 0];
            q.y = running; running += v[4 * j + 1];
            q.z = running; running += v[4 * j + 2];
            q.w = running; running += v[4 * j + 3];
            p.v[first / 4 + j] = q;
        }
    } else {
        U32Ptr p = U32Ptr(pc.dst);
        for (uint j = 0; j < SCAN_ITEMS_PER_THREAD; ++j) {
            if (first + j < pc.n) {
                p.v[first + j] = running;
            }
            running += v[j];
        }
    }
    if (pc.total != 0 && gl_LocalInvocationID.x == 0 && base + SCAN_TILE >= pc.n) {
        U32Ptr(pc.total).v[0] = tile_total;
    }
}
