#version 460
// One level's starting triples: each voxel inherits its parent's triple moved by spacing times
// the child offset projected into each role (level 0: the projection of the position times
// the spacing), then moves by the projected 3D jitter of its absolute position. CPU reference:
// synth/src/solid/cpu.rs (upsample_jitter_3d).
#include "common.glsl"
#include "synth/solid.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t parent;       // triples of the parent box (unused at level 0)
    uint64_t triples;      // out: 3 packed coordinates per voxel, x fastest
    ivec3 origin;
    uvec3 size;
    ivec3 parent_origin;
    uvec3 parent_size;
    uvec3 origin_mod;      // origin mod the exemplar side
    uint side;
    uint spacing;
    uint level;
    uint seed;
    uint strength;
    uint has_parent;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.size.x * pc.size.y * pc.size.z) {
        return;
    }
    uvec3 local = uvec3(i % pc.size.x, (i / pc.size.x) % pc.size.y, i / (pc.size.x * pc.size.y));
    ivec3 p = pc.origin + ivec3(local);
    uint t[3];
    if (pc.has_parent == 0u) {
        uvec3 q = (((pc.origin_mod + local) % pc.side) * pc.spacing) % pc.side;
        t[0] = synth_pack(q.yz);
        t[1] = synth_pack(q.xz);
        t[2] = synth_pack(q.xy);
    } else {
        uvec3 pl = uvec3((p >> 1) - pc.parent_origin);
        uint pi = (pl.z * pc.parent_size.y + pl.y) * pc.parent_size.x + pl.x;
        ivec3 child = (p & 1) * int(pc.spacing);
        for (uint r = 0; r < 3; r++) {
            t[r] = solid_moved(U32Ptr(pc.parent).v[pi * 3u + r], solid_project(r, child), pc.side);
        }
    }
    ivec3 j = solid_jitter(p, pc.level, pc.seed, pc.spacing, pc.strength);
    for (uint r = 0; r < 3; r++) {
        U32Ptr(pc.triples).v[i * 3u + r] = solid_moved(t[r], solid_project(r, j), pc.side);
    }
}
