#version 460
// One iteration of the coherence filter of one role: a pixel with more than
// SOLID_MAX_CANDIDATES candidates keeps those whose two other coordinates each continue (one
// step h along an image axis) a coordinate of some candidate of one of its 4 neighbours
// (+-h in the image); if none would survive it keeps its SOLID_MAX_CANDIDATES first (best
// crossbar) ones and is flagged. Smaller sets are copied. Order is preserved. One dispatch
// tests the candidates first .. first + chunk of every pixel and appends the survivors to those
// of earlier dispatches (llvmpipe stops an invocation's loops after 65535 iterations in all,
// and one candidate costs up to 800). CPU reference:
// compute/src/synth/solid/candidates.rs (coherence_step_cpu).
#include "common.glsl"
#include "synth/solid.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t in_triples;   // slots x 3 packed coordinates per pixel
    uint64_t in_errors;
    uint64_t in_counts;
    uint64_t out_triples;
    uint64_t out_errors;
    uint64_t out_counts;
    uint64_t fallbacks;    // out: 1 where the pixel fell back
    uint shift;
    uint spacing;
    uint slots;
    uint role1;            // the two other roles
    uint role2;
    uint first;            // first candidate this dispatch tests
    uint chunk;            // candidates it tests
} pc;

bool unit_step(uint a, uint b) {
    uint mask = (1u << pc.shift) - 1u;
    uvec2 ua = synth_unpack(a);
    uvec2 ub = synth_unpack(b);
    uint du = (ub.x - ua.x) & mask;
    uint dv = (ub.y - ua.y) & mask;
    uint s1 = pc.spacing & mask;
    uint s2 = (0u - pc.spacing) & mask;
    return (du == 0u && (dv == s1 || dv == s2)) || (dv == 0u && (du == s1 || du == s2));
}

// Whether some candidate of a neighbour has a coordinate of `role` one step from c.
bool continued(uint near[4], uint c, uint role) {
    for (uint n = 0; n < 4; n++) {
        uint q = near[n];
        uint count = U32Ptr(pc.in_counts).v[q];
        for (uint k = 0; k < count; k++) {
            if (unit_step(c, U32Ptr(pc.in_triples).v[(q * pc.slots + k) * 3u + role])) {
                return true;
            }
        }
    }
    return false;
}

void copy_slot(uint p, uint from, uint to) {
    uint a = p * pc.slots + from;
    uint b = p * pc.slots + to;
    for (uint r = 0; r < 3; r++) {
        U32Ptr(pc.out_triples).v[b * 3u + r] = U32Ptr(pc.in_triples).v[a * 3u + r];
    }
    U32Ptr(pc.out_errors).v[b] = U32Ptr(pc.in_errors).v[a];
}

void main() {
    uint p = uint(global_index());
    if (p >= (1u << (2u * pc.shift))) {
        return;
    }
    uint count = U32Ptr(pc.in_counts).v[p];
    if (count <= SOLID_MAX_CANDIDATES) {
        if (pc.first == 0u) {
            for (uint k = 0; k < count; k++) {
                copy_slot(p, k, k);
            }
            U32Ptr(pc.out_counts).v[p] = count;
            U32Ptr(pc.fallbacks).v[p] = 0u;
        }
        return;
    }
    if (pc.first >= count) {
        return;
    }
    uint kept = pc.first == 0u ? 0u : U32Ptr(pc.out_counts).v[p];
    int h = int(pc.spacing);
    uint near[4] = uint[4](solid_along(p, 0u, -h, pc.shift), solid_along(p, 0u, h, pc.shift),
                           solid_along(p, 1u, -h, pc.shift), solid_along(p, 1u, h, pc.shift));
    uint last = min(pc.first + pc.chunk, count);
    for (uint k = pc.first; k < last; k++) {
        uint slot = (p * pc.slots + k) * 3u;
        if (continued(near, U32Ptr(pc.in_triples).v[slot + pc.role1], pc.role1)
            && continued(near, U32Ptr(pc.in_triples).v[slot + pc.role2], pc.role2)) {
            copy_slot(p, k, kept);
            kept++;
        }
    }
    uint fell_back = 0u;
    if (last == count && kept == 0u) {
        for (uint k = 0; k < SOLID_MAX_CANDIDATES; k++) {
            copy_slot(p, k, k);
        }
        kept = SOLID_MAX_CANDIDATES;
        fell_back = 1u;
    }
    U32Ptr(pc.out_counts).v[p] = kept;
    if (pc.first == 0u || fell_back == 1u) {
        U32Ptr(pc.fallbacks).v[p] = fell_back;
    }
}
