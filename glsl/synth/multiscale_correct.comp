#version 460
// One correction subpass of the multiscale synthesizer: every interior pixel of one parity
// class takes, among the k-coherence candidates of its 3x3 neighbours (each neighbour's set at
// its own stack level, shifted back by the neighbour's offset at its own spacing), the one whose
// neighbourhood best matches the displayed neighbourhood (P Eq. 5: appearance plus the move of
// each pixel's cumulative transfer; the candidate composes the offering neighbour's transfer
// with its own). Integer SSD; ties keep the current state, then go to the smaller (meta,
// coordinate, transfer). Magnified pixels are not corrected. CPU reference:
// compute/src/synth/multiscale/cpu.rs (correct_subpass_multiscale).
#include "common.glsl"
#include "synth/multiscale.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t states;      // states of the region, updated in place
    uint64_t exemplars;   // uvec4 per exemplar: width, height, finest level, 0
    uint64_t members;     // 2 uvec4 per member: (appearance, record, candidate offsets, w | h << 16),
                          // (exemplar, level, spacing, 0)
    uint64_t lookup;      // member of exemplar * 16 + level, or 0xffffffff
    uint64_t appearance;  // 2 words per texel
    uint64_t records;     // 8 words per texel
    uint64_t candidates;  // uvec4 per candidate: coord, member | tb << 16, tr, tg
    uint64_t matrix;      // 8 x 3 ints: the offset move (appearance.rs)
    ivec2 origin;
    uvec2 size;
    uvec2 first;
    uvec2 count;
    uint k;
    uint penalty;
} pc;

const uint NONE = 0xffffffffu;

int mat[24];
bool mat_ready = false;

// The move of an appearance vector by offset t (1/16 levels), clamped to +-512.
void offset_move(ivec3 t, out ivec4 lo, out ivec4 hi) {
    if (t == ivec3(0)) {
        // The common case (one exemplar, or within one): no move, no 64-bit arithmetic.
        lo = ivec4(0);
        hi = ivec4(0);
        return;
    }
    if (!mat_ready) {
        // Loaded only where some transfer is not zero.
        for (int j = 0; j < 24; j++) {
            mat[j] = int(U32Ptr(pc.matrix).v[j]);
        }
        mat_ready = true;
    }
    int m[8];
    for (int d = 0; d < 8; d++) {
        int64_t v = int64_t(mat[d * 3]) * t.x + int64_t(mat[d * 3 + 1]) * t.y
            + int64_t(mat[d * 3 + 2]) * t.z;
        m[d] = int(clamp((v + 2048) >> 12, int64_t(-512), int64_t(512)));
    }
    lo = ivec4(m[0], m[1], m[2], m[3]);
    hi = ivec4(m[4], m[5], m[6], m[7]);
}

uint torus_axis(uint p, uint q, uint n) {
    uint d = p > q ? p - q : q - p;
    return min(d, n - d);
}

// Per neighbour, loaded once: state, member, spacing (0 when magnified), exemplar size and
// the member's appearance offset.
MsState around[9];
uint mem[9];
int sp[9];
uvec2 esize[9];
uint appoff[9];

// Appearance at neighbour n's coordinate moved by its spacing * d, plus its transfer's move.
void predict(int n, ivec2 d, ivec4 mlo, ivec4 mhi, out ivec4 lo, out ivec4 hi) {
    if (mem[n] == NONE) {
        lo = ivec4(0);
        hi = ivec4(0);
        return;
    }
    uvec2 e = esize[n];
    uvec2 c = synth_unpack(around[n].coord);
    c = uvec2(synth_wrap(c.x, d.x * sp[n], e.x), synth_wrap(c.y, d.y * sp[n], e.y));
    uvec2 a = UVec2Ptr(pc.appearance).v[appoff[n] + c.y * e.x + c.x];
    lo = synth_i8x4(a.x) + mlo;
    hi = synth_i8x4(a.y) + mhi;
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
    for (int n = 0; n < 9; n++) {
        uvec2 q = uvec2(ivec2(local) + ivec2(n % 3 - 1, n / 3 - 1));
        around[n] = MsStates(pc.states).v[q.y * pc.size.x + q.x];
        uint ex = ms_exemplar(around[n].meta);
        uint level = ms_level(around[n].meta);
        uvec4 e = UVec4Ptr(pc.exemplars).v[ex];
        esize[n] = e.xy;
        mem[n] = U32Ptr(pc.lookup).v[ex * 16u + min(level, e.z)];
        sp[n] = level == MS_MAGNIFIED ? 0 : 1 << (e.z - level);
        appoff[n] = mem[n] == NONE ? 0u : UVec4Ptr(pc.members).v[2u * mem[n]].x;
    }
    MsState current = around[4];
    if (ms_level(current.meta) == MS_MAGNIFIED || mem[4] == NONE) {
        return;
    }
    ivec4 mlo[9];
    ivec4 mhi[9];
    for (int n = 0; n < 9; n++) {
        offset_move(ivec3(around[n].tr, around[n].tg, around[n].tb), mlo[n], mhi[n]);
    }
    ivec4 sums[8];
    for (int j = 0; j < 4; j++) {
        ivec2 d = ivec2(2 * (j & 1) - 1, 2 * (j >> 1) - 1);
        int na = (d.y + 1) * 3 + d.x + 1;
        int nb = 4 + d.x;
        int nc = 4 + 3 * d.y;
        ivec4 alo, ahi, blo, bhi, clo, chi;
        predict(na, ivec2(0), mlo[na], mhi[na], alo, ahi);
        predict(nb, ivec2(0, d.y), mlo[nb], mhi[nb], blo, bhi);
        predict(nc, ivec2(d.x, 0), mlo[nc], mhi[nc], clo, chi);
        sums[2 * j] = alo + blo + clo;
        sums[2 * j + 1] = ahi + bhi + chi;
    }
    uint best_d = 0xffffffffu;
    uint best_nc = 0xffffffffu;
    uint best_meta = current.meta;
    uint best_coord = current.coord;
    ivec3 best_t = ivec3(current.tr, current.tg, current.tb);
    ivec3 cur_t = best_t;
    // Neighbours whose (member, base texel, transfer) repeat an earlier one offer the same
    // candidates with the same keys: evaluated once, from a compacted list (so a SIMD group
    // loops as often as its lane with the most distinct ones, as in correct.comp).
    uint bases[9];
    uint ubase[9];
    uint umem[9];
    ivec3 utr[9];
    int count = 0;
    for (int n = 0; n < 9; n++) {
        bases[n] = NONE;
        if (mem[n] == NONE || sp[n] == 0) {
            continue;
        }
        ivec2 d = ivec2(n % 3 - 1, n / 3 - 1);
        uvec2 e = esize[n];
        uvec2 c = synth_unpack(around[n].coord);
        c = uvec2(synth_wrap(c.x, -d.x * sp[n], e.x), synth_wrap(c.y, -d.y * sp[n], e.y));
        uint base = c.y * e.x + c.x;
        ivec3 tn = ivec3(around[n].tr, around[n].tg, around[n].tb);
        bool repeated = false;
        for (int m = 0; m < n; m++) {
            repeated = repeated || (bases[m] == base && mem[m] == mem[n]
                && ivec3(around[m].tr, around[m].tg, around[m].tb) == tn);
        }
        bases[n] = base;
        if (!repeated) {
            // Compacted by value, so that the candidate loop indexes no per-neighbour array
            // with a run-time index (which would keep those arrays out of registers).
            ubase[count] = base;
            umem[count] = mem[n];
            utr[count] = tn;
            count++;
        }
    }
    for (int u = 0; u < count; u++) {
        uint base = ubase[u];
        ivec3 tn = utr[u];
        uvec4 mi = UVec4Ptr(pc.members).v[2u * umem[u]];
        for (uint j = 0u; j < pc.k; j++) {
            uvec4 cw = UVec4Ptr(pc.candidates).v[mi.z + base * pc.k + j];
            uint cmember = cw.y & 0xffffu;
            ivec3 t = tn + ivec3(int(cw.z), int(cw.w), bitfieldExtract(int(cw.y), 16, 16));
            uvec4 cm0 = UVec4Ptr(pc.members).v[2u * cmember];
            uvec4 cm1 = UVec4Ptr(pc.members).v[2u * cmember + 1u];
            uvec2 cs = uvec2(cm0.w & 0xffffu, cm0.w >> 16);
            uvec2 cc = synth_unpack(cw.x);
            uint r = 2u * (cm0.y + cc.y * cs.x + cc.x);
            uvec4 rlo = UVec4Ptr(pc.records).v[r];
            uvec4 rhi = UVec4Ptr(pc.records).v[r + 1u];
            ivec4 vlo, vhi;
            offset_move(t, vlo, vhi);
            uint dist = word_distance(sums[0], rlo.x, vlo) + word_distance(sums[1], rlo.y, vhi)
                + word_distance(sums[2], rlo.z, vlo) + word_distance(sums[3], rlo.w, vhi)
                + word_distance(sums[4], rhi.x, vlo) + word_distance(sums[5], rhi.y, vhi)
                + word_distance(sums[6], rhi.z, vlo) + word_distance(sums[7], rhi.w, vhi);
            uint cmeta = cm1.x | (cm1.y << 8);
            if (pc.penalty != 0u) {
                uint spacing = cm1.z;
                uvec2 reach = (cs + spacing - 1u) / spacing;
                reach = uvec2(reach.x <= 2u ? reach.x : 0u, reach.y <= 2u ? reach.y : 0u);
                if (reach != uvec2(0u)) {
                    ivec2 lo = ivec2(0);
                    ivec2 hi = ivec2(0);
                    for (int m = 0; m < 9; m++) {
                        if (m == 4 || around[m].meta != cmeta) {
                            continue;
                        }
                        ivec2 dm = ivec2(m % 3 - 1, m / 3 - 1);
                        uvec2 u = synth_unpack(around[m].coord);
                        uvec2 cont = uvec2(synth_wrap(u.x, -dm.x * sp[m], cs.x),
                                           synth_wrap(u.y, -dm.y * sp[m], cs.y));
                        uint dx = torus_axis(cc.x, cont.x, cs.x);
                        uint dy = torus_axis(cc.y, cont.y, cs.y);
                        if (max(dx, dy) <= SYNTH_PERIOD_TOLERANCE) {
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
            }
            uint nc = (cmeta == current.meta && cw.x == current.coord && t == cur_t) ? 0u : 1u;
            bool better = dist != best_d ? dist < best_d
                : nc != best_nc ? nc < best_nc
                : cmeta != best_meta ? cmeta < best_meta
                : cw.x != best_coord ? cw.x < best_coord
                : t.x != best_t.x ? t.x < best_t.x
                : t.y != best_t.y ? t.y < best_t.y
                : t.z < best_t.z;
            if (better) {
                best_d = dist;
                best_nc = nc;
                best_meta = cmeta;
                best_coord = cw.x;
                best_t = t;
            }
        }
    }
    MsStates(pc.states).v[local.y * pc.size.x + local.x] =
        MsState(best_coord, best_meta, best_t.x, best_t.y, best_t.z);
}
