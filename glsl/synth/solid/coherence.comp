#version 460
// One iteration of the coherence filter of one role, one workgroup per pixel: a pixel with more
// than SOLID_MAX_CANDIDATES candidates keeps those whose two other coordinates each continue
// (one step h along an image axis) a coordinate of some candidate of one of its 4 neighbours
// (+-h in the image); if none would survive it keeps its SOLID_MAX_CANDIDATES first (best
// crossbar) ones and is flagged. Smaller sets are copied. Order is preserved. The workgroup
// puts the neighbours' coordinates of each of the two roles into a hash set in shared memory,
// so a candidate costs 4 look-ups per coordinate instead of a scan of up to 400 coordinates.
// CPU reference: synth/src/solid/candidates.rs (coherence_step_cpu).
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
    uint first_pixel;      // pixel of workgroup 0
} pc;

// Open addressing, linear probing; a packed coordinate is below 2^24 (sides up to 256), so all
// ones is empty.
const uint TABLE = 1024u;
const uint EMPTY = 0xffffffffu;
shared uint table[2][TABLE];
shared uint survives[SOLID_KEPT];
shared uint kept_total;

uint slot_of(uint c) {
    return (c * 2654435761u) >> 22;
}

void insert(uint t, uint c) {
    uint h = slot_of(c);
    for (uint probe = 0u; probe < TABLE; probe++) {
        uint was = atomicCompSwap(table[t][h], EMPTY, c);
        if (was == EMPTY || was == c) {
            return;
        }
        h = (h + 1u) & (TABLE - 1u);
    }
}

bool holds(uint t, uint c) {
    uint h = slot_of(c);
    for (uint probe = 0u; probe < TABLE; probe++) {
        uint v = table[t][h];
        if (v == c) {
            return true;
        }
        if (v == EMPTY) {
            return false;
        }
        h = (h + 1u) & (TABLE - 1u);
    }
    return false;
}

// Whether some neighbour candidate's coordinate in table t is one step h from c.
bool continued(uint t, uint c) {
    uint m = 1u << pc.shift;
    int h = int(pc.spacing);
    return holds(t, solid_moved(c, ivec2(h, 0), m)) || holds(t, solid_moved(c, ivec2(-h, 0), m))
        || holds(t, solid_moved(c, ivec2(0, h), m)) || holds(t, solid_moved(c, ivec2(0, -h), m));
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
    uint p = pc.first_pixel + group_index();
    uint lid = gl_LocalInvocationID.x;
    uint w = gl_WorkGroupSize.x;
    uint count = U32Ptr(pc.in_counts).v[p];
    if (count <= SOLID_MAX_CANDIDATES) {
        // The same for the whole workgroup, so no invocation is left at a barrier.
        for (uint k = lid; k < count; k += w) {
            copy_slot(p, k, k);
        }
        if (lid == 0u) {
            U32Ptr(pc.out_counts).v[p] = count;
            U32Ptr(pc.fallbacks).v[p] = 0u;
        }
        return;
    }
    for (uint k = lid; k < TABLE; k += w) {
        table[0][k] = EMPTY;
        table[1][k] = EMPTY;
    }
    barrier();
    int h = int(pc.spacing);
    uint near[4] = uint[4](solid_along(p, 0u, -h, pc.shift), solid_along(p, 0u, h, pc.shift),
                           solid_along(p, 1u, -h, pc.shift), solid_along(p, 1u, h, pc.shift));
    for (uint n = 0u; n < 4u; n++) {
        uint q = near[n];
        uint cq = U32Ptr(pc.in_counts).v[q];
        for (uint k = lid; k < cq; k += w) {
            uint slot = (q * pc.slots + k) * 3u;
            insert(0u, U32Ptr(pc.in_triples).v[slot + pc.role1]);
            insert(1u, U32Ptr(pc.in_triples).v[slot + pc.role2]);
        }
    }
    barrier();
    for (uint k = lid; k < count; k += w) {
        uint slot = (p * pc.slots + k) * 3u;
        bool keep = continued(0u, U32Ptr(pc.in_triples).v[slot + pc.role1])
            && continued(1u, U32Ptr(pc.in_triples).v[slot + pc.role2]);
        survives[k] = keep ? 1u : 0u;
    }
    barrier();
    // Survivors keep their order: each one's place is the survivors before it.
    for (uint k = lid; k < count; k += w) {
        if (survives[k] == 1u) {
            uint place = 0u;
            for (uint o = 0u; o < k; o++) {
                place += survives[o];
            }
            copy_slot(p, k, place);
        }
    }
    if (lid == 0u) {
        uint kept = 0u;
        for (uint o = 0u; o < count; o++) {
            kept += survives[o];
        }
        kept_total = kept;
    }
    barrier();
    uint kept = kept_total;
    if (kept == 0u) {
        for (uint k = lid; k < SOLID_MAX_CANDIDATES; k += w) {
            copy_slot(p, k, k);
        }
        kept = SOLID_MAX_CANDIDATES;
    }
    if (lid == 0u) {
        U32Ptr(pc.out_counts).v[p] = kept;
        U32Ptr(pc.fallbacks).v[p] = kept_total == 0u ? 1u : 0u;
    }
}
