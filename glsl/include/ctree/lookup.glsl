// Random access to a compressed random-access tree (compute/src/ctree/; Lefebvre and Hoppe
// 2007, thesis §4.1.3), in integers only: the twin of compute/src/ctree/lookup.rs, equal to it
// bit for bit. A primal lattice of 2^n + 1 nodes per axis; level l >= 1 has 2^(l-1) + 1. The
// forest holds the dense values of levels 1..F (i16) and, at level F, the byte address of each
// node's record (CTREE_NO_SUBTREE if none). A record is one byte of the node's own 7-bit code,
// then one PointerOrData byte per child the node has (x fastest among its open axes): high bit
// clear, the leaf child's code; set, the child's record lies (byte & 0x7f) * scale[l] bytes
// after the end of this record.
//
// Use from any kernel:
//     #include "common.glsl"
//     #include "ctree/lookup.glsl"
//     int v = ctree_lookup_fixed(p, pos, lod);   // pos: finest spacings << CTREE_POS_FRAC_BITS,
//                                                // lod << CTREE_LOD_FRAC_BITS; fixed-point value
//     float g = ctree_sample(p, uv, lod);        // uv in [0,1]^d over the field's samples
// The struct is 56 bytes in scalar layout, the bytes of the Rust `CtreeParams` (same order):
//     struct CtreeParams {
//         uint64_t bytes;        // packed records, 4 per uint, little-endian
//         uint64_t mipmap;       // i16 values of levels 1..F, 2 per uint
//         uint64_t indirection;  // uint per level-F node
//         uint64_t levels;       // int steps[L + 1], uint scales[L], uint mip_starts[F]
//         uint dims;             // 2 or 3
//         uint n;                // L = n + 1
//         uint forest;           // F
//         uvec3 size;            // the field's samples per axis
//     };
#ifndef LAZYSOLID_CTREE_LOOKUP_GLSL
#define LAZYSOLID_CTREE_LOOKUP_GLSL

struct CtreeParams {
    uint64_t bytes;
    uint64_t mipmap;
    uint64_t indirection;
    uint64_t levels;
    uint dims;
    uint n;
    uint forest;
    uvec3 size;
};

struct CtreeCell {
    uint level;
    uvec3 base;
    int values[8];
    uint records[8];
};

uint ctree_byte(CtreeParams p, uint address) {
    return (U32Ptr(p.bytes).v[address >> 2] >> (8u * (address & 3u))) & 0xffu;
}

int ctree_code(uint b) {
    return bitfieldExtract(int(b), 0, 7);
}

int ctree_step(CtreeParams p, uint l) {
    return int(U32Ptr(p.levels).v[l]);
}

uint ctree_scale(CtreeParams p, uint l) {
    return U32Ptr(p.levels).v[p.n + 2u + l];
}

uint ctree_mip_start(CtreeParams p, uint l) {
    return U32Ptr(p.levels).v[2u * p.n + 3u + (l - 1u)];
}

uint ctree_side(uint l) {
    return (1u << (l - 1u)) + 1u;
}

uint ctree_index(CtreeParams p, uint l, uvec3 q) {
    uint m = ctree_side(l);
    uint i = q.x + m * q.y;
    if (p.dims == 3u) {
        i += m * m * q.z;
    }
    return i;
}

uvec3 ctree_corner(uvec3 base, uint e) {
    return base + uvec3(e & 1u, (e >> 1) & 1u, (e >> 2) & 1u);
}

int ctree_mip_value(CtreeParams p, uint index) {
    uint w = U32Ptr(p.mipmap).v[index >> 1];
    return bitfieldExtract(int(w), int(16u * (index & 1u)), 16);
}

CtreeCell ctree_forest_cell(CtreeParams p, uint l, uvec3 pos) {
    uint shift = p.n + 1u - l + CTREE_POS_FRAC_BITS;
    uint last_cell = ctree_side(l) - 2u;
    CtreeCell cell;
    cell.level = l;
    cell.base = uvec3(0u);
    for (uint k = 0u; k < p.dims; ++k) {
        cell.base[k] = min(pos[k] >> shift, last_cell);
    }
    uint start = ctree_mip_start(p, l);
    for (uint e = 0u; e < 8u; ++e) {
        cell.values[e] = 0;
        cell.records[e] = CTREE_NO_SUBTREE;
    }
    for (uint e = 0u; e < (1u << p.dims); ++e) {
        uint i = ctree_index(p, l, ctree_corner(cell.base, e));
        cell.values[e] = ctree_mip_value(p, start + i);
        if (l == p.forest) {
            cell.records[e] = U32Ptr(p.indirection).v[i];
        }
    }
    return cell;
}

bool ctree_has_subtree(CtreeParams p, CtreeCell cell) {
    for (uint e = 0u; e < (1u << p.dims); ++e) {
        if (cell.records[e] != CTREE_NO_SUBTREE) {
            return true;
        }
    }
    return false;
}

// One level down (the caller checks ctree_has_subtree first).
CtreeCell ctree_descend(CtreeParams p, CtreeCell cell, uvec3 pos) {
    uint l = cell.level;
    uint bits = p.n + 1u - l + CTREE_POS_FRAC_BITS;
    uint half_cell = 1u << (bits - 1u);
    uvec3 sub = uvec3(0u);
    for (uint k = 0u; k < p.dims; ++k) {
        sub[k] = (pos[k] - (cell.base[k] << bits)) >= half_cell ? 1u : 0u;
    }
    int step = ctree_step(p, l + 1u);
    uint scale = ctree_scale(p, l);
    uint last = ctree_side(l) - 1u;
    CtreeCell next;
    next.level = l + 1u;
    next.base = 2u * cell.base + sub;
    for (uint c = 0u; c < 8u; ++c) {
        next.values[c] = 0;
        next.records[c] = CTREE_NO_SUBTREE;
    }
    uint brood = 1u << p.dims;
    for (uint c = 0u; c < brood; ++c) {
        uint owner = 0u;
        uint child = 0u;
        uint odd = 0u;
        uvec3 t = uvec3(0u);
        for (uint k = 0u; k < p.dims; ++k) {
            t[k] = sub[k] + ((c >> k) & 1u);
            if (t[k] == 2u) {
                owner |= 1u << k;
            } else if (t[k] == 1u) {
                child |= 1u << k;
                odd += 1u;
            }
        }
        int sum = 0;
        for (uint e = 0u; e < brood; ++e) {
            bool takes = true;
            for (uint k = 0u; k < p.dims; ++k) {
                uint bit = (e >> k) & 1u;
                takes = takes && (t[k] == 1u || (t[k] == 0u && bit == 0u) || (t[k] == 2u && bit == 1u));
            }
            if (takes) {
                sum += cell.values[e];
            }
        }
        int prediction = sum >> odd;
        uint record = cell.records[owner];
        int code = 0;
        uint sub_record = CTREE_NO_SUBTREE;
        if (record != CTREE_NO_SUBTREE) {
            uvec3 q = ctree_corner(cell.base, owner);
            // The owner's children: two along each axis where it is not on the upper face.
            uint slot = 0u;
            uint stride = 1u;
            for (uint k = 0u; k < p.dims; ++k) {
                if (q[k] < last) {
                    slot += stride * ((child >> k) & 1u);
                    stride *= 2u;
                }
            }
            uint size = 1u + stride;
            uint b = ctree_byte(p, record + 1u + slot);
            if ((b & 0x80u) != 0u) {
                uint address = record + size + (b & 0x7fu) * scale;
                code = ctree_code(ctree_byte(p, address));
                sub_record = address;
            } else {
                code = ctree_code(b);
            }
        }
        next.values[c] = prediction + code * step;
        next.records[c] = sub_record;
    }
    return next;
}

int ctree_interpolate(CtreeParams p, CtreeCell cell, uvec3 pos) {
    uint bits = p.n + 1u - cell.level + CTREE_POS_FRAC_BITS;
    int v[8] = cell.values;
    uint count = 1u << p.dims;
    for (uint k = 0u; k < p.dims; ++k) {
        uint rel = pos[k] - (cell.base[k] << bits);
        int w = int(bits >= CTREE_WEIGHT_BITS ? rel >> (bits - CTREE_WEIGHT_BITS)
                                              : rel << (CTREE_WEIGHT_BITS - bits));
        count /= 2u;
        for (uint e = 0u; e < count; ++e) {
            int a = v[2u * e];
            int b = v[2u * e + 1u];
            v[e] = a + (((b - a) * w) >> CTREE_WEIGHT_BITS);
        }
    }
    return v[0];
}

// The values at level l and (if `finer`) one level finer, as compute/src/ctree/lookup.rs.
ivec2 ctree_evaluate(CtreeParams p, uint l, uvec3 pos, bool finer) {
    if (l < p.forest) {
        int at = ctree_interpolate(p, ctree_forest_cell(p, l, pos), pos);
        int next = finer ? ctree_interpolate(p, ctree_forest_cell(p, l + 1u, pos), pos) : at;
        return ivec2(at, next);
    }
    CtreeCell cell = ctree_forest_cell(p, p.forest, pos);
    while (cell.level < l && ctree_has_subtree(p, cell)) {
        cell = ctree_descend(p, cell, pos);
    }
    int at = ctree_interpolate(p, cell, pos);
    if (!finer || cell.level < l || l == p.n + 1u || !ctree_has_subtree(p, cell)) {
        return ivec2(at);
    }
    return ivec2(at, ctree_interpolate(p, ctree_descend(p, cell, pos), pos));
}

int ctree_lookup_fixed(CtreeParams p, uvec3 pos, uint lod) {
    pos = min(pos, (p.size - 1u) << CTREE_POS_FRAC_BITS);
    uint finest = (p.n + 1u) << CTREE_LOD_FRAC_BITS;
    uint target = max(finest - min(lod, finest), 1u << CTREE_LOD_FRAC_BITS);
    uint level = target >> CTREE_LOD_FRAC_BITS;
    int w = int(target & ((1u << CTREE_LOD_FRAC_BITS) - 1u));
    ivec2 v = ctree_evaluate(p, level, pos, w > 0);
    return v.x + (((v.y - v.x) * w) >> CTREE_LOD_FRAC_BITS);
}

// The fixed-point lattice position of uv (the field's sample centres at (i + 0.5) / size),
// as CompressedTree::position in Rust.
uvec3 ctree_position(CtreeParams p, vec3 uv) {
    uvec3 pos = uvec3(0u);
    for (uint k = 0u; k < p.dims; ++k) {
        precise float x = uv[k] * float(p.size[k] << CTREE_POS_FRAC_BITS);
        precise float y = x - float(1u << (CTREE_POS_FRAC_BITS - 1u));
        float top = float((p.size[k] - 1u) << CTREE_POS_FRAC_BITS);
        pos[k] = uint(clamp(floor(y), 0.0, top));
    }
    return pos;
}

// The field at uv, in grey levels, at level of detail lod (0 the finest; fractions blend).
float ctree_sample(CtreeParams p, vec3 uv, float lod) {
    uint l = uint(clamp(lod, 0.0, 31.0) * float(1u << CTREE_LOD_FRAC_BITS));
    int v = ctree_lookup_fixed(p, ctree_position(p, uv), l);
    return float(v) / float(1u << CTREE_VALUE_FRAC_BITS);
}

#endif
