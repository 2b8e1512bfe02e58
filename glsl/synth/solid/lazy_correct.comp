#version 460
// Lazy synthesis, subpass `stage` of a level: every needed voxel of the subpass's class that
// is needed at this stage and lacks the version the subpass produces reads its 18 plane
// neighbours at the versions they hold after the previous stage (through the level's table),
// decides as correct.comp does (synth/solid_correct.glsl), and stores the new version. Voxels
// of one class read only other classes, so the subpass updates them independently. CPU
// reference: LazySolidCpu::request in synth/src/solid/lazy/state_cpu.rs.
#include "common.glsl"
#include "synth/lazy.glsl"
#include "synth/solid_correct.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t levels;
    uint64_t table;    // the level's 15 analysis, candidate and penalty addresses (see correct.comp)
    uint64_t keys;     // stage-tagged: the last stage each voxel is needed at
    uint64_t slots;
    uint64_t errors;   // out: counts missing neighbours (must stay 0)
    uint n;
    uint level;
    uint stage;        // 1-based subpass
    uint cls;          // its class place
    uint version;      // the version it produces
    uint side;
    uint spacing;
    uint keep_current; // the current triple competes even when not gathered
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t tk = U64Ptr(pc.keys).v[i];
    if (lazy_untag_stage(tk) < pc.stage) {
        return;
    }
    ivec3 p = lazy_position(lazy_untag_key(tk));
    if (lazy_class(p) != pc.cls) {
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
        if (sq == HASH_NOT_FOUND) {
            atomicAdd(U32Ptr(pc.errors).v[0], 1u);
            return;
        }
        around[n] = lazy_version(l, sq, lazy_version_at(pc.stage - 1u, lazy_class(q)));
    }
    uvec3 t = solid_correct(around, pc.table, pc.side, pc.spacing, pc.keep_current);
    lazy_store(l, s, pc.version, t);
    U32Ptr(l.counts).v[s] = pc.version + 1u;
}
