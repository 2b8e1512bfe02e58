// One correction subpass of the multiscale synthesizer: every interior pixel of one parity
// class takes, among the k-coherence candidates of its 3x3 neighbours (each neighbour's set at
// its own stack level, shifted back by the neighbour's offset at its own spacing), the one whose
// neighbourhood best matches the displayed neighbourhood (P Eq. 5: appearance plus the move of
// each pixel's cumulative transfer; the candidate composes the offering neighbour's transfer
// with its own). Integer SSD; ties keep the current state, then go to the smaller (meta,
// coordinate, transfer). Magnified pixels are not corrected.
//
// Pixels are working states over the depth set's packed layout (multiscale_enter.comp,
// synth/src/multiscale/atlas.rs): every shift is precomputed per texel, and texel
// order is (meta, coordinate) order, so the kernel reads what the 2D one reads (correct.comp)
// plus the transfers.
//
// Four variants: MS_TRANSFERS 0 for depths where no transfer can be other than zero (no depth so
// far has a candidate with one; none is read), MS_PERIOD 0 for subpasses where no candidate can
// be period-penalized (no pixel sits at a level offering one: multiscale_select.comp picks the
// variant on the device, from the flag the MS_PERIOD 0 kernels keep). A CPU driver (llvmpipe)
// runs every branch under a lane mask whether or not a lane takes it, so work a dispatch does
// not need must be absent from its kernel, not skipped; and every load is a gather per lane,
// hence few words per state.
//
// CPU reference: synth/src/multiscale/cpu.rs (correct_subpass_multiscale).
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t texel;       // working texel index per pixel, updated in place
    uint64_t transfer;    // working transfer per pixel (ms_pack_transfer), updated in place
    uint64_t texels;      // per texel: packed coordinate, meta (| offers-period flag << 16)
    uint64_t continued;   // per texel: 8 continued texels, neighbours in row order but the centre
    uint64_t appearance;  // per texel: 5 appearance vectors (2 words each): self, -x, +x, -y, +y
    uint64_t records;     // per texel: 8 words
    uint64_t cand_texel;  // per texel: k candidate texels (| MS_OFFERS_PERIOD)
    uint64_t cand_extra;  // per texel, k: transfer r | g << 16, b
    uint64_t cand_period; // per texel, k: x | y << 8 | meta << 16, (w-1) | (h-1) << 8 | reach << 16
    uint64_t exemplars;   // uvec4 per exemplar: width, height, finest level, 0
    uint64_t matrix;      // 8 x 3 ints: the offset move (appearance.rs)
    uint64_t control;     // MS_CONTROL_WORDS words (multiscale.glsl)
    uvec2 size;
    uvec2 first;
    uvec2 count;
    uint k;
    uint penalty;         // the period penalty (read by the MS_PERIOD variants)
} pc;

int mat[24];

// The move of an appearance vector by offset t (1/16 levels), clamped to +-512. 32-bit
// arithmetic is exact: |t| <= MS_MAX_TRANSFER and |mat| <= 2^16 (appearance.rs,
// OFFSET_MATRIX_MAX).
void offset_move(ivec3 t, out ivec4 lo, out ivec4 hi) {
    int m[8];
    for (int d = 0; d < 8; d++) {
        int v = mat[d * 3] * t.x + mat[d * 3 + 1] * t.y + mat[d * 3 + 2] * t.z;
        const int move = int(MULTISCALE_MAX_OFFSET_MOVE);
        m[d] = clamp((v + (1 << (MULTISCALE_OFFSET_MOVE_SHIFT - 1))) >> MULTISCALE_OFFSET_MOVE_SHIFT,
                     -move, move);
    }
    lo = ivec4(m[0], m[1], m[2], m[3]);
    hi = ivec4(m[4], m[5], m[6], m[7]);
}

#if MS_PERIOD
uint torus_axis(uint p, uint q, uint n) {
    uint d = p > q ? p - q : q - p;
    return min(d, n - d);
}
#endif

// The appearance texel index a predicts at its stored shift `slot`, plus its transfer's move;
// a magnified pixel predicts its texel's own (an absent level is the zero texel after the last,
// flagged fixed: nothing).
void predict(uint a, uint slot, ivec4 mlo, ivec4 mhi, out ivec4 lo, out ivec4 hi) {
    slot = (a & MS_FIXED) != 0u ? 0u : slot;
    uvec2 v = UVec2Ptr(pc.appearance).v[(a & ~MS_FIXED) * 5u + slot];
    lo = synth_i8x4(v.x) + mlo;
    hi = synth_i8x4(v.y) + mhi;
}

uint word_distance(ivec4 s, uint w, ivec4 mv) {
    ivec4 d = s - 3 * (synth_i8x4(w) + mv);
    return uint(d.x * d.x) + uint(d.y * d.y) + uint(d.z * d.z) + uint(d.w * d.w);
}

void main() {
    uint i = uint(global_index());
    if (i >= pc.count.x * pc.count.y) {
        return;
    }
    uvec2 local = pc.first + 2 * uvec2(i % pc.count.x, i / pc.count.x);
    uint at[9];
    ivec3 tr[9];
    for (int n = 0; n < 9; n++) {
        uvec2 q = uvec2(ivec2(local) + ivec2(n % 3 - 1, n / 3 - 1));
        uint p = q.y * pc.size.x + q.x;
        at[n] = U32Ptr(pc.texel).v[p];
#if MS_TRANSFERS
        tr[n] = ms_unpack_transfer(UVec2Ptr(pc.transfer).v[p]);
#else
        tr[n] = ivec3(0);
#endif
    }
    uint current = at[4];
    if ((current & MS_FIXED) != 0u) {
        return;
    }
    ivec4 mlo[9];
    ivec4 mhi[9];
#if MS_TRANSFERS
    for (int j = 0; j < 24; j++) {
        mat[j] = int(U32Ptr(pc.matrix).v[j]);
    }
    for (int n = 0; n < 9; n++) {
        offset_move(tr[n], mlo[n], mhi[n]);
    }
#else
    for (int n = 0; n < 9; n++) {
        mlo[n] = ivec4(0);
        mhi[n] = ivec4(0);
    }
#endif
    ivec4 sums[8];
    for (int j = 0; j < 4; j++) {
        ivec2 d = ivec2(2 * (j & 1) - 1, 2 * (j >> 1) - 1);
        int na = (d.y + 1) * 3 + d.x + 1;
        int nb = 4 + d.x;
        int nc = 4 + 3 * d.y;
        ivec4 alo, ahi, blo, bhi, clo, chi;
        predict(at[na], 0u, mlo[na], mhi[na], alo, ahi);
        predict(at[nb], d.y < 0 ? 3u : 4u, mlo[nb], mhi[nb], blo, bhi);
        predict(at[nc], d.x < 0 ? 1u : 2u, mlo[nc], mhi[nc], clo, chi);
        sums[2 * j] = alo + blo + clo;
        sums[2 * j + 1] = ahi + bhi + chi;
    }
    // Neighbours whose (continued texel, transfer) repeat an earlier one offer the same
    // candidates with the same keys: evaluated once, from a list compacted by value (so a SIMD
    // group loops as often as its lane with the most distinct ones, as in correct.comp).
    // bases[n]: the texel continuing neighbour n's patch at the centre (MS_ABSENT: none).
    uint bases[9];
    uint ubase[9];
#if MS_TRANSFERS
    ivec3 utr[9];
#endif
    int count = 0;
    for (int n = 0; n < 9; n++) {
        uint a = at[n];
        bool still = (a & MS_FIXED) != 0u;
        uint base = n == 4 ? a
            : U32Ptr(pc.continued).v[(still ? 0u : a) * 8u + uint(n < 4 ? n : n - 1)];
        base = still ? MS_ABSENT : base;
        bool repeated = still;
        for (int m = 0; m < n; m++) {
            repeated = repeated || (bases[m] == base && tr[m] == tr[n]);
        }
        bases[n] = base;
        if (!repeated) {
            ubase[count] = base;
#if MS_TRANSFERS
            utr[count] = tr[n];
#endif
            count++;
        }
    }
#if MS_PERIOD
    // Each neighbour's continued texel as (coordinate, meta), for the period test.
    uvec2 continued_texel[9];
    for (int m = 0; m < 9; m++) {
        continued_texel[m] = m == 4 || bases[m] == MS_ABSENT ? uvec2(0u, MS_ABSENT)
            : UVec2Ptr(pc.texels).v[bases[m]] & uvec2(0xffffffffu, 0xffffu);
    }
#endif
    ivec3 cur_t = tr[4];
    uint best_d = 0xffffffffu;
    uint best_nc = 0xffffffffu;
    uint best_a = current;
    uint best_offers = 0u;
    ivec3 best_t = cur_t;
    for (int u = 0; u < count; u++) {
        uint base = ubase[u];
#if MS_TRANSFERS
        ivec3 tn = utr[u];
#endif
        for (uint j = 0u; j < pc.k; j++) {
            uint slot = base * pc.k + j;
            uint flagged = U32Ptr(pc.cand_texel).v[slot];
            uint c = flagged & ~MS_OFFERS_PERIOD;
            uvec4 rlo = UVec4Ptr(pc.records).v[2u * c];
            uvec4 rhi = UVec4Ptr(pc.records).v[2u * c + 1u];
#if MS_TRANSFERS
            uvec2 extra = UVec2Ptr(pc.cand_extra).v[slot];
            ivec3 t = clamp(tn + ms_unpack_transfer(extra), -MS_MAX_TRANSFER, MS_MAX_TRANSFER);
            ivec4 vlo, vhi;
            offset_move(t, vlo, vhi);
#else
            ivec3 t = ivec3(0);
            ivec4 vlo = ivec4(0);
            ivec4 vhi = ivec4(0);
#endif
            uint dist = word_distance(sums[0], rlo.x, vlo) + word_distance(sums[1], rlo.y, vhi)
                + word_distance(sums[2], rlo.z, vlo) + word_distance(sums[3], rlo.w, vhi)
                + word_distance(sums[4], rhi.x, vlo) + word_distance(sums[5], rhi.y, vhi)
                + word_distance(sums[6], rhi.z, vlo) + word_distance(sums[7], rhi.w, vhi);
#if MS_PERIOD
            {
                // The extent of the patch the candidate would continue, over the neighbours
                // at its level whose continued texel lies within the tolerance; penalized
                // where its level spans at most 2 of its pixels along an axis the extent
                // reaches across (period.rs, spans_period).
                uvec2 pw = UVec2Ptr(pc.cand_period).v[slot];
                uvec2 cc = uvec2(pw.x & 0xffu, (pw.x >> 8) & 0xffu);
                uint cmeta = pw.x >> 16;
                uvec2 cs = uvec2(pw.y & 0xffu, (pw.y >> 8) & 0xffu) + 1u;
                uvec2 reach = uvec2((pw.y >> 16) & 0xfu, (pw.y >> 20) & 0xfu);
                ivec2 lo = ivec2(0);
                ivec2 hi = ivec2(0);
                for (int m = 0; m < 9; m++) {
                    uvec2 cont = synth_unpack(continued_texel[m].x);
                    uint dx = torus_axis(cc.x, cont.x, cs.x);
                    uint dy = torus_axis(cc.y, cont.y, cs.y);
                    if (continued_texel[m].y == cmeta && max(dx, dy) <= SYNTH_PERIOD_TOLERANCE) {
                        ivec2 dm = ivec2(m % 3 - 1, m / 3 - 1);
                        lo = min(lo, dm);
                        hi = max(hi, dm);
                    }
                }
                uvec2 extent = uvec2(hi - lo);
                if ((reach.x != 0u && extent.x >= reach.x)
                    || (reach.y != 0u && extent.y >= reach.y)) {
                    dist += pc.penalty;
                }
            }
#endif
            uint nc = (c == current && t == cur_t) ? 0u : 1u;
            bool better = dist != best_d ? dist < best_d
                : nc != best_nc ? nc < best_nc
                : c != best_a ? c < best_a
                : t.x != best_t.x ? t.x < best_t.x
                : t.y != best_t.y ? t.y < best_t.y
                : t.z < best_t.z;
            if (better) {
                best_d = dist;
                best_nc = nc;
                best_a = c;
                best_t = t;
                best_offers = flagged >> 31;
            }
        }
    }
    uint p = local.y * pc.size.x + local.x;
    U32Ptr(pc.texel).v[p] = best_a;
#if !MS_PERIOD
    // The pixel moved to a level offering candidates that can be period-penalized: the next
    // subpass runs the test (multiscale_select.comp). (Its old level was counted already.)
    if (best_offers != 0u) {
        atomicOr(U32Ptr(pc.control).v[0], 1u);
    }
#endif
#if MS_TRANSFERS
    UVec2Ptr(pc.transfer).v[p] = ms_pack_transfer(best_t);
#endif
}
