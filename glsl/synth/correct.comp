#version 460
// One correction subpass: every interior pixel of one parity class takes, among the k-coherence
// candidates of its 3x3 neighbours (shifted back by the neighbour's offset), the one whose
// exemplar neighbourhood best matches its synthesized neighbourhood (integer SSD; ties keep the
// current coordinate, then go to the smaller packed one; a candidate whose coherent patch would
// span an exemplar period gets a penalty added, see synth/src/period.rs). The other
// classes are only read, so the update is in place. The neighbourhood is the 4-diagonal one of Lefebvre & Hoppe 2006:
// per diagonal the sum of 3 predicted appearance vectors, against 3x the candidate's
// precomputed record. CPU reference: synth/src/cpu.rs (correct_subpass) and
// synth/src/neighbourhood.rs.
#include "common.glsl"
#include "synth/synth.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t coords;          // packed coordinates of the region, updated in place
    uint64_t appearance;      // 2 words (8 x i8) per exemplar pixel
    uint64_t neighbourhoods;  // 8 words (4 diagonals x 8 x i8) per exemplar pixel
    uint64_t coherence;       // k packed coordinates per exemplar pixel
    ivec2 origin;
    uvec2 size;
    uvec2 first;              // first interior local position of the class
    uvec2 count;              // class pixels per row and column
    uvec2 exemplar;
    uint spacing;
    uint k;
    uvec2 reach;              // period_reach of the level; 0: the axis is never penalized
    uint penalty;             // added to a candidate spanning a period; 0: no test
} pc;

// The appearance vector at packed coordinate c moved by spacing * d, as two words of 4 x i8.
uvec2 appearance_at(uint c, ivec2 d) {
    uvec2 e = synth_unpack(c);
    e = uvec2(synth_wrap(e.x, d.x, pc.exemplar.x), synth_wrap(e.y, d.y, pc.exemplar.y));
    return UVec2Ptr(pc.appearance).v[e.y * pc.exemplar.x + e.x];
}

// Toroidal distance of p and q along an axis of n pixels.
uint torus_axis(uint p, uint q, uint n) {
    uint d = p > q ? p - q : q - p;
    return min(d, n - d);
}

// Squared distance of 4 synthesized sums and 3x the 4 components of word w.
uint word_distance(ivec4 s, uint w) {
    ivec4 d = s - 3 * synth_i8x4(w);
    return uint(d.x * d.x + d.y * d.y + d.z * d.z + d.w * d.w);
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.count.x * pc.count.y) {
        return;
    }
    uvec2 local = pc.first + 2 * uvec2(i % pc.count.x, i / pc.count.x);
    int s = int(pc.spacing);
    uint around[9];
    for (int n = 0; n < 9; n++) {
        uvec2 q = uvec2(ivec2(local) + ivec2(n % 3 - 1, n / 3 - 1));
        around[n] = U32Ptr(pc.coords).v[q.y * pc.size.x + q.x];
    }
    // Synthesized neighbourhood: per diagonal (order (-1,-1), (1,-1), (-1,1), (1,1)) the sum of
    // the appearance predicted by the diagonal pixel and the two edge pixels next to it; two
    // ivec4 of sums per diagonal, in the word order of the exemplar records.
    ivec4 sums[8];
    for (int j = 0; j < 4; j++) {
        ivec2 d = ivec2(2 * (j & 1) - 1, 2 * (j >> 1) - 1);
        uvec2 a = appearance_at(around[(d.y + 1) * 3 + d.x + 1], ivec2(0));
        uvec2 b = appearance_at(around[4 + d.x], ivec2(0, d.y * s));
        uvec2 c = appearance_at(around[4 + 3 * d.y], ivec2(d.x * s, 0));
        sums[2 * j] = synth_i8x4(a.x) + synth_i8x4(b.x) + synth_i8x4(c.x);
        sums[2 * j + 1] = synth_i8x4(a.y) + synth_i8x4(b.y) + synth_i8x4(c.y);
    }
    // Ranked by (distance, 0 for the current coordinate else 1 + packed candidate): the
    // current coordinate survives every tie, so zero jitter keeps the exemplar tiling.
    uint current = around[4];
    uint best_d = 0xffffffffu;
    uint best_rank = 0xffffffffu;
    uint best_c = current;
    // In coherent regions most neighbours, shifted back, name the same exemplar pixel and so
    // the same candidates. Each is evaluated once (a repeat has the same distance and rank, so
    // skipping it cannot change the choice), from a compacted list: the loop then runs as
    // many times as the lane with the most distinct ones needs, not over the union of the
    // positions where some lane has a new one.
    // continued[n]: the coordinate that continues neighbour n's patch at the centre.
    uvec2 continued[9];
    uint bases[9];
    uint unique[9];
    uint count = 0;
    for (int n = 0; n < 9; n++) {
        ivec2 d = ivec2(n % 3 - 1, n / 3 - 1);
        uvec2 u = synth_unpack(around[n]);
        continued[n] = uvec2(synth_wrap(u.x, -d.x * s, pc.exemplar.x),
                             synth_wrap(u.y, -d.y * s, pc.exemplar.y));
        bases[n] = continued[n].y * pc.exemplar.x + continued[n].x;
        bool repeated = false;
        for (int m = 0; m < n; m++) {
            repeated = repeated || bases[m] == bases[n];
        }
        if (!repeated) {
            unique[count] = bases[n];
            count++;
        }
    }
    for (uint i = 0; i < count; i++) {
        uint base = unique[i];
        for (uint j = 0; j < pc.k; j++) {
            uint cand = U32Ptr(pc.coherence).v[base * pc.k + j];
            uvec2 c = synth_unpack(cand);
            uint e = 2 * (c.y * pc.exemplar.x + c.x);
            uvec4 lo = UVec4Ptr(pc.neighbourhoods).v[e];
            uvec4 hi = UVec4Ptr(pc.neighbourhoods).v[e + 1];
            uint dist = word_distance(sums[0], lo.x) + word_distance(sums[1], lo.y)
                + word_distance(sums[2], lo.z) + word_distance(sums[3], lo.w)
                + word_distance(sums[4], hi.x) + word_distance(sums[5], hi.y)
                + word_distance(sums[6], hi.z) + word_distance(sums[7], hi.w);
            if (pc.penalty != 0u) {
                // The extent of the patch the candidate would continue: itself and the
                // neighbours it continues (synth/src/period.rs, spans_period).
                ivec2 lo = ivec2(0);
                ivec2 hi = ivec2(0);
                for (int n = 0; n < 9; n++) {
                    uint dx = torus_axis(c.x, continued[n].x, pc.exemplar.x);
                    uint dy = torus_axis(c.y, continued[n].y, pc.exemplar.y);
                    if (n != 4 && max(dx, dy) <= SYNTH_PERIOD_TOLERANCE) {
                        ivec2 d = ivec2(n % 3 - 1, n / 3 - 1);
                        lo = min(lo, d);
                        hi = max(hi, d);
                    }
                }
                uvec2 extent = uvec2(hi - lo);
                if ((pc.reach.x != 0u && extent.x >= pc.reach.x)
                    || (pc.reach.y != 0u && extent.y >= pc.reach.y)) {
                    dist += pc.penalty;
                }
            }
            uint rank = cand == current ? 0u : cand + 1u;
            if (dist < best_d || (dist == best_d && rank < best_rank)) {
                best_d = dist;
                best_rank = rank;
                best_c = cand;
            }
        }
    }
    U32Ptr(pc.coords).v[local.y * pc.size.x + local.x] = best_c;
}
