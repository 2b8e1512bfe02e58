#version 460
// One correction subpass: every interior pixel of one parity class takes, among the k-coherence
// candidates of its 3x3 neighbours (shifted back by the neighbour's offset), the one whose
// exemplar neighbourhood of appearance vectors best matches its synthesized neighbourhood
// (integer SSD; ties keep the current coordinate, then go to the smaller packed one). The
// other classes are only read, so the update is in place. CPU reference:
// compute/src/synth/cpu.rs (correct_subpass).
#include "common.glsl"
#include "synth/synth.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t coords;      // packed coordinates of the region, updated in place
    uint64_t appearance;  // 4 words (8 x i16) per exemplar pixel
    uint64_t coherence;   // k packed coordinates per exemplar pixel
    ivec2 origin;
    uvec2 size;
    uvec2 first;          // first interior local position of the class
    uvec2 count;          // class pixels per row and column
    uvec2 exemplar;
    uint spacing;
    uint k;
} pc;

uvec4 appearance_at(uint c) {
    uvec2 e = synth_unpack(c);
    return UVec4Ptr(pc.appearance).v[e.y * pc.exemplar.x + e.x];
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.count.x * pc.count.y) {
        return;
    }
    uvec2 local = pc.first + 2 * uvec2(i % pc.count.x, i / pc.count.x);
    int s = int(pc.spacing);
    uint neighbours[9];
    uvec4 synthesized[9];
    for (int n = 0; n < 9; n++) {
        uvec2 q = uvec2(ivec2(local) + ivec2(n % 3 - 1, n / 3 - 1));
        neighbours[n] = U32Ptr(pc.coords).v[q.y * pc.size.x + q.x];
        synthesized[n] = appearance_at(neighbours[n]);
    }
    // Ranked by (distance, 0 for the current coordinate else 1 + packed candidate): the
    // current coordinate survives every tie, so zero jitter keeps the exemplar tiling.
    uint current = neighbours[4];
    uint best_d = 0xffffffffu;
    uint best_rank = 0xffffffffu;
    uint best_c = current;
    for (int n = 0; n < 9; n++) {
        ivec2 d = ivec2(n % 3 - 1, n / 3 - 1);
        uvec2 u = synth_unpack(neighbours[n]);
        uint base = synth_wrap(u.y, -d.y * s, pc.exemplar.y) * pc.exemplar.x
            + synth_wrap(u.x, -d.x * s, pc.exemplar.x);
        for (uint j = 0; j < pc.k; j++) {
            uint cand = U32Ptr(pc.coherence).v[base * pc.k + j];
            uvec2 c = synth_unpack(cand);
            uint dist = 0;
            for (int m = 0; m < 9; m++) {
                if (m == 4) {
                    continue;
                }
                ivec2 e = ivec2(m % 3 - 1, m / 3 - 1) * s;
                uint ec = synth_pack(uvec2(synth_wrap(c.x, e.x, pc.exemplar.x),
                                           synth_wrap(c.y, e.y, pc.exemplar.y)));
                dist += synth_distance(synthesized[m], appearance_at(ec));
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
