#version 460
// Lazy synthesis, before a level's correction: for every stage, the stretch of the visiting
// order (lazy_prepare.comp's keys, sorted with the voxels' indices) that holds the voxels the
// stage may correct, and the workgroup counts of lazy_correct.comp's indirect dispatch over
// it. On an ordered level a stage corrects one class; with the keys sorted on (no work, class,
// last stage latest first), its voxels needed at that stage or later are one stretch, found by
// two binary searches. The correction still checks every voxel it visits, so a stretch may
// only hold more voxels than the stage corrects, never fewer (stages past 63 share a key).
// CPU reference: stage_range in synth/src/solid/lazy/stage_ranges.rs.
#include "common.glsl"
#include "synth/lazy.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t order_keys; // the level's visiting keys, sorted
    uint64_t ranges;     // out: LAZY_RANGE_WORDS words per stage (stage 1 first)
    uint n;
    uint stages;
    uint parallel;       // 1: every stage corrects every class
    uint whole;          // 1: every stretch is all n voxels (the keys' own order, unsorted)
    uint width;          // lazy_correct.comp's workgroup size
} pc;

// The first place whose key is at least k.
uint lower_bound(uint k) {
    uint lo = 0u, hi = pc.n;
    while (lo < hi) {
        uint mid = lo + (hi - lo) / 2u;
        if (U32Ptr(pc.order_keys).v[mid] < k) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return lo;
}

void main() {
    uint stage = uint(global_index()) + 1u;
    if (stage > pc.stages) {
        return;
    }
    uint first = 0u;
    uint count = pc.n;
    if (pc.whole == 0u) {
        uint cls = pc.parallel != 0u ? 0u : (stage - 1u) % 8u;
        first = lower_bound(lazy_order_key(0u, cls, 63u));
        count = lower_bound(lazy_order_key(0u, cls, stage) + 1u) - first;
    }
    uvec3 g = lazy_groups(count, pc.width);
    uint w = (stage - 1u) * LAZY_RANGE_WORDS;
    U32Ptr(pc.ranges).v[w] = g.x;
    U32Ptr(pc.ranges).v[w + 1u] = g.y;
    U32Ptr(pc.ranges).v[w + 2u] = g.z;
    U32Ptr(pc.ranges).v[w + 3u] = first;
    U32Ptr(pc.ranges).v[w + 4u] = count;
}
