// The per-voxel decision of a solid correction subpass, shared by the dense kernel
// (synth/solid/correct.comp) and the lazy one (synth/solid/lazy_correct.comp): among the
// voxel's current triple and the candidates gathered in each role's plane, the triple whose
// three exemplar neighbourhoods, each with its coordinate's usage penalty (balance.rs), best
// match the three planes through the voxel (see correct.comp). CPU reference: correct_voxel in synth/src/solid/cpu.rs.
#ifndef LAZYSOLID_SOLID_CORRECT_GLSL
#define LAZYSOLID_SOLID_CORRECT_GLSL

#include "synth/solid.glsl"

ivec4 sums[3][8];
uint64_t appearance[3];
uint64_t records[3];
uint64_t candidates[3];
uint64_t counts[3];
uint64_t penalties[3];
uint solid_side;

uint word_distance(ivec4 s, uint w) {
    ivec4 d = s - 3 * synth_i8x4(w);
    return uint(d.x * d.x + d.y * d.y + d.z * d.z + d.w * d.w);
}

uvec2 appearance_at(uint role, uint c, ivec2 d) {
    uvec2 e = synth_unpack(solid_moved(c, d, solid_side));
    return UVec2Ptr(appearance[role]).v[e.y * solid_side + e.x];
}

uint role_distance(uint r, uint c) {
    uvec2 u = synth_unpack(c);
    uint e = 2u * (u.y * solid_side + u.x);
    uvec4 lo = UVec4Ptr(records[r]).v[e];
    uvec4 hi = UVec4Ptr(records[r]).v[e + 1u];
    return U32Ptr(penalties[r]).v[e >> 1u]
        + word_distance(sums[r][0], lo.x) + word_distance(sums[r][1], lo.y)
        + word_distance(sums[r][2], lo.z) + word_distance(sums[r][3], lo.w)
        + word_distance(sums[r][4], hi.x) + word_distance(sums[r][5], hi.y)
        + word_distance(sums[r][6], hi.z) + word_distance(sums[r][7], hi.w);
}

// The distance of triple t, or some value above `bound` once the partial sum exceeds it.
uint distance_of(uvec3 t, uint bound) {
    uint dist = role_distance(0u, t.x);
    if (dist > bound) return dist;
    dist += role_distance(1u, t.y);
    if (dist > bound) return dist;
    return dist + role_distance(2u, t.z);
}

// (distance, 0 for the current triple else 1, triple) lexicographically smaller.
bool better(uint d, uint rank, uvec3 t, uint bd, uint br, uvec3 bt) {
    if (d != bd) return d < bd;
    if (rank != br) return rank < br;
    if (t.x != bt.x) return t.x < bt.x;
    if (t.y != bt.y) return t.y < bt.y;
    return t.z < bt.z;
}

// The corrected triple of the voxel whose 3x3x3 neighbourhood (x fastest, 13 the centre) is
// `around`; only the 19 voxels of the three planes through the centre are read. `table` holds
// the level's 15 buffer addresses (see correct.comp). The current triple competes only as one
// of the gathered candidates unless `keep_current` is set (an ablation for `bench solid`): a
// merely translated triple has a near-zero distance inside its block and would otherwise win
// although its three exemplar colours disagree.
// The parts of the decision a profile runs (`parts` of solid_correct; CorrectParts in
// synth/src/solid/lazy/gpu/mod.rs): reading the neighbours, then the neighbourhood sums, then each
// gathered set's own-role distance, then everything. Below SOLID_PARTS_ALL the current triple
// is returned, kept dependent on what was computed so that the compiler keeps that work.
const uint SOLID_PARTS_NEIGHBOURS = 1u;
const uint SOLID_PARTS_SUMS = 2u;
const uint SOLID_PARTS_OWN = 3u;
const uint SOLID_PARTS_ALL = 4u;

// t, made to depend on x (never changed by it in practice).
uvec3 solid_depend(uvec3 t, uint x) {
    return x == 0x9e3779b9u ? t ^ uvec3(1u) : t;
}

uvec3 solid_correct(uvec3 around[27], uint64_t table, uint side, uint spacing, uint keep_current,
                    uint parts) {
    if (parts == SOLID_PARTS_NEIGHBOURS) {
        uint x = 0u;
        for (int n = 0; n < 27; n++) {
            ivec3 d = ivec3(n % 3, (n / 3) % 3, n / 9) - 1;
            if (d.x == 0 || d.y == 0 || d.z == 0) {
                x ^= around[n].x ^ around[n].y ^ around[n].z;
            }
        }
        return solid_depend(around[13], x);
    }
    solid_side = side;
    for (uint r = 0; r < 3; r++) {
        appearance[r] = U64Ptr(table).v[r];
        records[r] = U64Ptr(table).v[3u + r];
        candidates[r] = U64Ptr(table).v[6u + r];
        counts[r] = U64Ptr(table).v[9u + r];
        penalties[r] = U64Ptr(table).v[12u + r];
    }
    int s = int(spacing);
    // Per role, the synthesized neighbourhood of the plane through the voxel: per diagonal
    // (plane order (-1,-1), (1,-1), (-1,1), (1,1)) the sum of the appearance predicted by the
    // diagonal voxel and the two edge voxels next to it.
    for (uint r = 0; r < 3; r++) {
        for (int j = 0; j < 4; j++) {
            ivec2 d = ivec2(2 * (j & 1) - 1, 2 * (j >> 1) - 1);
            ivec3 wd = r == 0u ? ivec3(0, d) : (r == 1u ? ivec3(d.x, 0, d.y) : ivec3(d, 0));
            ivec3 wu = r == 0u ? ivec3(0, d.x, 0) : ivec3(d.x, 0, 0);
            ivec3 wv = r == 2u ? ivec3(0, d.y, 0) : ivec3(0, 0, d.y);
            uint cd = around[(wd.z + 1) * 9 + (wd.y + 1) * 3 + wd.x + 1][r];
            uint cu = around[(wu.z + 1) * 9 + (wu.y + 1) * 3 + wu.x + 1][r];
            uint cv = around[(wv.z + 1) * 9 + (wv.y + 1) * 3 + wv.x + 1][r];
            uvec2 a = appearance_at(r, cd, ivec2(0));
            uvec2 b = appearance_at(r, cu, ivec2(0, d.y * s));
            uvec2 c = appearance_at(r, cv, ivec2(d.x * s, 0));
            sums[r][2 * j] = synth_i8x4(a.x) + synth_i8x4(b.x) + synth_i8x4(c.x);
            sums[r][2 * j + 1] = synth_i8x4(a.y) + synth_i8x4(b.y) + synth_i8x4(c.y);
        }
    }
    uvec3 current = around[13];
    if (parts == SOLID_PARTS_SUMS) {
        uint x = 0u;
        for (uint r = 0; r < 3; r++) {
            for (int j = 0; j < 8; j++) {
                x ^= uint(sums[r][j].x ^ sums[r][j].y ^ sums[r][j].z ^ sums[r][j].w);
            }
        }
        return solid_depend(current, x);
    }
    uint own_sum = 0u;
    // "No best yet": above every distance (at most 3 * 1.9e7), the rank of a non-current
    // triple; the first gathered candidate replaces it (sets are never empty).
    uint best_d = 0xffffffffu;
    uint best_r = 1u;
    uvec3 best_t = current;
    if (keep_current != 0u) {
        best_d = distance_of(current, 0xffffffffu);
        best_r = 0u;
    }
    for (uint r = 0; r < 3; r++) {
        uint unique[9];
        uint n_unique = 0u;
        for (int n = 0; n < 9; n++) {
            ivec2 d = ivec2(n % 3, n / 3) - 1;
            ivec3 w = r == 0u ? ivec3(0, d) : (r == 1u ? ivec3(d.x, 0, d.y) : ivec3(d, 0));
            uint c = around[(w.z + 1) * 9 + (w.y + 1) * 3 + w.x + 1][r];
            uvec2 u = synth_unpack(solid_moved(c, -d * s, solid_side));
            uint base = u.y * solid_side + u.x;
            bool repeated = false;
            for (uint m = 0u; m < n_unique; m++) {
                repeated = repeated || unique[m] == base;
            }
            if (!repeated) {
                unique[n_unique] = base;
                n_unique++;
            }
        }
        // The two other roles, in increasing order.
        uint o1 = r == 0u ? 1u : 0u;
        uint o2 = r == 2u ? 1u : 2u;
        for (uint k = 0u; k < n_unique; k++) {
            uint base = unique[k];
            // Every candidate of pixel `base` in role r has `base` as its role-r coordinate:
            // that share of the distance once per set, and the whole set skipped when it
            // alone is above the best (the shares are never negative; as in correct_voxel).
            uint own = role_distance(r, synth_pack(uvec2(base % solid_side, base / solid_side)));
            if (parts == SOLID_PARTS_OWN) {
                own_sum += own;
                continue;
            }
            if (own > best_d) continue;
            uint cnt = U32Ptr(counts[r]).v[base];
            for (uint c = 0u; c < cnt; c++) {
                uint slot = (base * SOLID_MAX_CANDIDATES + c) * 3u;
                uvec3 t = uvec3(U32Ptr(candidates[r]).v[slot], U32Ptr(candidates[r]).v[slot + 1u],
                                U32Ptr(candidates[r]).v[slot + 2u]);
                uint dist = own + role_distance(o1, t[o1]);
                if (dist <= best_d) dist += role_distance(o2, t[o2]);
                uint rank = t == current ? 0u : 1u;
                if (better(dist, rank, t, best_d, best_r, best_t)) {
                    best_d = dist;
                    best_r = rank;
                    best_t = t;
                }
            }
        }
    }
    if (parts == SOLID_PARTS_OWN) {
        return solid_depend(current, own_sum);
    }
    return best_t;
}

#endif
