// What the compressed-tree builder's kernels (glsl/ctree/ctree_*.comp; compute/src/ctree/
// builder.rs) share: the push block, the per-level buffer table and statistics, and the primal
// lattice of compute/src/ctree/lattice.rs. Level l >= 1 has 2^(l-1) + 1 nodes per axis; level 0
// is the root, whose children are the domain's corners.
#ifndef LAZYSOLID_CTREE_BUILD_GLSL
#define LAZYSOLID_CTREE_BUILD_GLSL

#extension GL_EXT_shader_atomic_int64 : require

layout(push_constant, scalar) uniform Push {
    uint64_t field;     // int fixed-point samples, x fastest
    uint64_t table;     // per level: CTREE_TABLE_WORDS device addresses
    uint64_t stats;     // per level: CTREE_STATS_WORDS uint64_t
    uint64_t scratch;   // per pass: keys, flags, candidate totals or block sizes
    uint64_t scratch2;  // per pass: the preorder permutation or block offsets
    uint64_t bytes;     // the packed records, 4 per uint
    uvec3 size;
    uint dims;
    uint n;
    uint level;
    uint count;
    uint step;
    uint first_scale;
    uint records;
    uint candidates;
    uint forest;
    uint border;        // CTREE_BORDER_*
} pc;

layout(buffer_reference, scalar, buffer_reference_align = 4) buffer I32Ptr { int v[]; };

uint64_t ct_buffer(uint l, uint which) {
    return U64Ptr(pc.table).v[CTREE_TABLE_WORDS * l + which];
}

I32Ptr ct_values(uint l) { return I32Ptr(ct_buffer(l, CTREE_TABLE_VALUES)); }
I32Ptr ct_codes(uint l) { return I32Ptr(ct_buffer(l, CTREE_TABLE_CODES)); }
U32Ptr ct_internal(uint l) { return U32Ptr(ct_buffer(l, CTREE_TABLE_INTERNAL)); }
U32Ptr ct_blocks(uint l) { return U32Ptr(ct_buffer(l, CTREE_TABLE_BLOCKS)); }
U32Ptr ct_addresses(uint l) { return U32Ptr(ct_buffer(l, CTREE_TABLE_ADDRESSES)); }
U32Ptr ct_records(uint l) { return U32Ptr(ct_buffer(l, CTREE_TABLE_RECORDS)); }

uint ct_stat_index(uint l, uint which) {
    return CTREE_STATS_WORDS * l + which;
}

uint ct_side(uint l) {
    return (1u << (l - 1u)) + 1u;
}

uint ct_count(uint l) {
    if (l == 0u) {
        return 1u;
    }
    uint m = ct_side(l);
    return pc.dims == 3u ? m * m * m : m * m;
}

uint ct_index(uint l, uvec3 q) {
    uint m = ct_side(l);
    uint i = q.x + m * q.y;
    if (pc.dims == 3u) {
        i += m * m * q.z;
    }
    return i;
}

uvec3 ct_coords(uint l, uint i) {
    if (l == 0u) {
        return uvec3(0u);
    }
    uint m = ct_side(l);
    uint z = pc.dims == 3u ? i / (m * m) : 0u;
    uint r = i - z * m * m;
    return uvec3(r % m, r / m, z);
}

// Axes along which the node has an upper child (all of them at the root).
uvec3 ct_open(uint l, uvec3 q) {
    uvec3 open = uvec3(0u);
    for (uint k = 0u; k < pc.dims; ++k) {
        open[k] = (l == 0u || q[k] < ct_side(l) - 1u) ? 1u : 0u;
    }
    return open;
}

bool ct_child_exists(uvec3 open, uint c) {
    for (uint k = 0u; k < pc.dims; ++k) {
        if (((c >> k) & 1u) == 1u && open[k] == 0u) {
            return false;
        }
    }
    return true;
}

uint ct_child_count(uvec3 open) {
    uint count = 1u;
    for (uint k = 0u; k < pc.dims; ++k) {
        count *= open[k] == 1u ? 2u : 1u;
    }
    return count;
}

uvec3 ct_child(uint l, uvec3 q, uint c) {
    uvec3 base = l == 0u ? uvec3(0u) : 2u * q;
    return base + uvec3(c & 1u, (c >> 1) & 1u, (c >> 2) & 1u);
}

uvec3 ct_finest(uint l, uvec3 q) {
    return l == 0u ? uvec3(0u) : q * (1u << (pc.n + 1u - l));
}

// Whether the node at level-l coordinates q codes a residual: a sample, or with
// CTREE_BORDER_ANCHORED the first node past a border (field::ScalarField::codes).
bool ct_codes_residual(uint l, uvec3 q) {
    uint spacing = l == 0u ? 0u : 1u << (pc.n + 1u - l);
    uint past = pc.border == CTREE_BORDER_ANCHORED ? spacing : 0u;
    return all(lessThan(ct_finest(l, q), pc.size + past));
}

// The field at level-l coordinates q (its border repeated past its size).
int ct_target(uint l, uvec3 q) {
    uint spacing = l == 0u ? 0u : 1u << (pc.n + 1u - l);
    uvec3 p = min(q * spacing, pc.size - 1u);
    return I32Ptr(pc.field).v[p.x + pc.size.x * (p.y + pc.size.y * p.z)];
}

// Offset, after the padding to a multiple of `scale`, of each internal child's block, as
// pack::place: returns the block's end after the last internal child (the bytes after the
// record), the padding in `padding` and false in `fits` when an offset passes 127 * scale.
uint ct_place(uint l, uint i, uint scale, out uint padding, out bool fits) {
    uvec3 q = ct_coords(l, i);
    uvec3 open = ct_open(l, q);
    uint offset = 0u;
    padding = 0u;
    fits = true;
    for (uint c = 0u; c < (1u << pc.dims); ++c) {
        if (!ct_child_exists(open, c)) {
            continue;
        }
        uint b = ct_blocks(l + 1u).v[ct_index(l + 1u, ct_child(l, q, c))];
        if (b == 0u) {
            continue;
        }
        uint pad = (scale - offset % scale) % scale;
        offset += pad;
        padding += pad;
        if (offset / scale > CTREE_MAX_OFFSET) {
            fits = false;
        }
        offset += b;
    }
    return offset;
}

#endif
