#version 460
// Compressed-tree layout, level pc.level >= F, one invocation per record: writes the record
// (its own code, then a PointerOrData byte per child) at its address, and the addresses of its
// internal children's records (after the record and the padding to the level's scale).
#include "common.glsl"
#include "ctree/build.glsl"

void ct_put(uint address, uint b) {
    atomicOr(U32Ptr(pc.bytes).v[address >> 2], (b & 0xffu) << (8u * (address & 3u)));
}

void main() {
    uint j = uint(global_index());
    if (j >= pc.records) {
        return;
    }
    uint l = pc.level;
    uint i = ct_records(l).v[j];
    uint a = ct_addresses(l).v[i];
    uvec3 q = ct_coords(l, i);
    uvec3 open = ct_open(l, q);
    uint size = 1u + ct_child_count(open);
    uint scale = uint(U64Ptr(pc.stats).v[ct_stat_index(l, CTREE_STAT_BEST)] & 0xfffffffful);
    ct_put(a, uint(ct_codes(l).v[i]) & 0x7fu);
    uint offset = 0u;
    uint slot = 0u;
    for (uint c = 0u; c < (1u << pc.dims); ++c) {
        if (!ct_child_exists(open, c)) {
            continue;
        }
        uint child = ct_index(l + 1u, ct_child(l, q, c));
        uint b = ct_blocks(l + 1u).v[child];
        if (b != 0u) {
            offset += (scale - offset % scale) % scale;
            ct_put(a + 1u + slot, 0x80u | (offset / scale));
            ct_addresses(l + 1u).v[child] = a + size + offset;
            offset += b;
        } else {
            ct_put(a + 1u + slot, uint(ct_codes(l + 1u).v[child]) & 0x7fu);
        }
        slot += 1u;
    }
}
