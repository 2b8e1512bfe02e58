#version 460
// Lazy synthesis, stage `stage` of a level: every needed voxel of the class the stage corrects
// (every class on a parallel level) that is needed at this stage and lacks the version the
// stage produces reads its 18 plane neighbours at the versions they hold after the previous
// stage (through the level's table; a neighbour read only as upsampled is not stored and is
// upsampled in place from its parent), decides as correct.comp does (synth/solid_correct.glsl),
// and stores the new version beside the ones it read, so the voxels update independently. CPU
// reference: LazySolidCpu::request in synth/src/solid/lazy/state_cpu.rs.
#include "common.glsl"
#include "synth/lazy.glsl"
#include "synth/solid_correct.glsl"
#include "synth/lazy_upsample.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t table;    // the level's 15 analysis, candidate and penalty addresses (see correct.comp)
    uint64_t keys;     // stage-tagged: the last stage each voxel is needed at
    uint64_t order;    // the voxels' visiting order (lazy_prepare.comp)
    uint64_t ranges;   // the stages' stretches of it (lazy_stage_ranges.comp)
    uint64_t slots;
    uint64_t errors;   // out: counts missing neighbours (must stay 0)
    uint level;
    uint stage;        // 1-based subpass
    uint cls;          // its class place, or LAZY_ALL_CLASSES
    uint version;      // the version it produces
    uint side;
    uint spacing;
    uint keep_current; // the current triple competes even when not gathered
    uint seed;         // the jitter's, for neighbours read only as upsampled
    uint strength;
} pc;

// Which parts of the decision run (SOLID_PARTS_*): all of them, except in a profile
// (`lazysolid bench lazy --profile-correction`), whose versions are then wrong.
layout(constant_id = 1) const uint PARTS = SOLID_PARTS_ALL;

void main() {
    // Dispatched indirectly over the stage's stretch of the visiting order.
    uint g = uint(global_index());
    uint w = (pc.stage - 1u) * LAZY_RANGE_WORDS;
    if (g >= U32Ptr(pc.ranges).v[w + 4u]) {
        return;
    }
    uint i = U32Ptr(pc.order).v[U32Ptr(pc.ranges).v[w + 3u] + g];
    uint64_t tk = U64Ptr(pc.keys).v[i];
    if (lazy_untag_stage(tk) < pc.stage) {
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(tk));
    if (!lazy_corrects(pc.cls, lazy_class(p))) {
        return;
    }
    LazyLevel l = LazyLevels(pc.levels).v[pc.level];
    uint s = U32Ptr(pc.slots).v[i];
    if (U32Ptr(l.counts).v[s] != pc.version) {
        return;
    }
    uvec3 around[27];
    for (int n = 0; n < 27; n++) {
        ivec3 d = ivec3(n % 3, (n / 3) % 3, n / 9) - 1;
        if (d.x != 0 && d.y != 0 && d.z != 0) {
            continue;
        }
        ivec3 q = p + d;
        uint sq = n == 13 ? s : lazy_slot(l, q);
        uint v = lazy_version_at(l, pc.stage - 1u, lazy_class(q));
        if (sq != HASH_NOT_FOUND) {
            around[n] = lazy_version(l, sq, v);
        } else if (v != 0u || !lazy_upsampled(pc.levels, pc.level, q, pc.side, pc.spacing,
                                               pc.seed, pc.strength, around[n])) {
            // Only a voxel read as upsampled may be missing, and then its parent may not.
            atomicAdd(U32Ptr(pc.errors).v[0], 1u);
            return;
        }
    }
    uvec3 t = solid_correct(around, pc.table, pc.side, pc.spacing, pc.keep_current, PARTS);
    lazy_store(l, s, pc.version, t);
    U32Ptr(l.counts).v[s] = pc.version + 1u;
}
