// Version 0 of a lazy voxel: its parent's final triple (found in the level above's table)
// moved by spacing times the child offset projected into each role (level 0: the projection
// of the position times the spacing), then moved by the projected 3D jitter. Exactly
// upsample_jitter.comp per voxel; CPU reference: upsample_voxel in synth/src/solid/cpu.rs.
// lazy_upsample.comp stores it; lazy_correct.comp computes it in place for a neighbour that
// is read only as upsampled and therefore not stored (synth/src/solid/lazy/deps.rs).
#ifndef LAZYSOLID_LAZY_UPSAMPLE_GLSL
#define LAZYSOLID_LAZY_UPSAMPLE_GLSL

#include "synth/lazy.glsl"
#include "synth/solid.glsl"

// Version 0 of position p of `level` into t; false when its parent is not stored.
bool lazy_upsampled(uint64_t levels, uint level, ivec3 p, uint side, uint spacing, uint seed,
                    uint strength, out uvec3 t) {
    uint b[3];
    if (level == 0u) {
        uvec3 q = ((uvec3(p & int(side - 1u))) * spacing) % side;
        b[0] = synth_pack(q.yz);
        b[1] = synth_pack(q.xz);
        b[2] = synth_pack(q.xy);
    } else {
        LazyLevel above = LazyLevels(levels).v[level - 1u];
        uint ps = lazy_slot(above, p >> 1);
        if (ps == HASH_NOT_FOUND) {
            t = uvec3(0u);
            return false;
        }
        uvec3 parent = lazy_version(above, ps, above.stride - 1u);
        ivec3 child = (p & 1) * int(spacing);
        for (uint r = 0; r < 3; r++) {
            b[r] = solid_moved(parent[r], solid_project(r, child), side);
        }
    }
    ivec3 j = solid_jitter(p, level, seed, spacing, strength);
    for (uint r = 0; r < 3; r++) {
        t[r] = solid_moved(b[r], solid_project(r, j), side);
    }
    return true;
}

#endif
