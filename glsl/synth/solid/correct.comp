#version 460
// One correction subpass of the volume synthesizer: every voxel of one parity class inside the
// subpass's box (first, count: every other voxel per axis) takes, among its current triple and
// the candidate triples gathered in each role's plane (each of the 3x3 voxels of the plane
// through the voxel perpendicular to the role's axis: its coordinate in that role shifted back
// by its offset in the plane), the one whose three exemplar neighbourhoods best match the
// three planes through the voxel (per plane the 2D synthesizer's 4-diagonal, 3-prediction
// appearance sums, integer SSD, plus the coordinate's usage penalty). The current triple competes only when gathered (unless
// keep_current). Ties keep the current triple, then go to the smallest triple.
// Each distinct shifted-back pixel of a role is evaluated once (a repeat gives the same
// candidates, so it cannot change the choice), and a candidate's distance stops once its
// partial sum exceeds the best (it cannot win). A parallel pass (step 1) updates every voxel
// of the box, reading the state before the pass from `source` (a copy); an ordered subpass
// (step 2) reads and writes `triples`, since a class reads only other classes.
// CPU reference: synth/src/solid/cpu.rs.
#include "common.glsl"
#include "synth/solid_correct.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t triples;          // 3 packed coordinates per voxel, written
    uint64_t source;           // the same layout, read (triples itself in an ordered subpass)
    // 15 addresses (push constants hold only 128 bytes on lavapipe), per role r:
    // [r] appearance, 2 words (8 x i8) per exemplar pixel; [3 + r] 4-diagonal records, 8 words
    // per pixel; [6 + r] SOLID_MAX_CANDIDATES x 3 packed coordinates per pixel; [9 + r] valid
    // candidates per pixel; [12 + r] usage penalty per pixel (synth/src/solid/balance.rs).
    uint64_t table;
    ivec3 origin;
    uvec3 size;
    uvec3 first;               // first local position of the class inside the subpass's box
    uvec3 count;               // class voxels per axis
    uint side;
    uint spacing;
    uint keep_current;         // the current triple competes even when not gathered
    uint step;                 // 2: one parity class (ordered subpass), 1: every voxel (parallel)
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.count.x * pc.count.y * pc.count.z) {
        return;
    }
    uvec3 local = pc.first
        + pc.step * uvec3(i % pc.count.x, (i / pc.count.x) % pc.count.y, i / (pc.count.x * pc.count.y));
    // The 19 voxels of the three planes through the voxel; the 8 corners (no zero offset)
    // lie in none of them and are never read.
    uvec3 around[27];
    for (int n = 0; n < 27; n++) {
        ivec3 d = ivec3(n % 3, (n / 3) % 3, n / 9) - 1;
        if (d.x != 0 && d.y != 0 && d.z != 0) {
            continue;
        }
        uvec3 q = uvec3(ivec3(local) + d);
        uint vi = (q.z * pc.size.y + q.y) * pc.size.x + q.x;
        around[n] = uvec3(U32Ptr(pc.source).v[vi * 3u], U32Ptr(pc.source).v[vi * 3u + 1u],
                          U32Ptr(pc.source).v[vi * 3u + 2u]);
    }
    uvec3 best_t = solid_correct(around, pc.table, pc.side, pc.spacing, pc.keep_current,
                                 SOLID_PARTS_ALL);
    uint vi = (local.z * pc.size.y + local.y) * pc.size.x + local.x;
    U32Ptr(pc.triples).v[vi * 3u] = best_t.x;
    U32Ptr(pc.triples).v[vi * 3u + 1u] = best_t.y;
    U32Ptr(pc.triples).v[vi * 3u + 2u] = best_t.z;
}
