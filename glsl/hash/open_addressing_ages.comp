#version 460
// Plain open addressing (first come, first served, no Robin Hood), for the age histogram that
// Robin Hood is compared against (thesis Fig. 4.16): ages[i] = the probe step at which key i
// found an empty slot, or 0 when it found none within max_age steps. 64-bit cells holding
// key + 1 only.
#include "common.glsl"
#extension GL_EXT_shader_atomic_int64 : require
#include "hash/probe.glsl"

layout(push_constant, scalar) uniform Push {
    uint64_t cells;
    uint64_t fastmod_m;
    uint64_t keys;
    uint64_t ages;
    uint n;
    uint table_size;
    uint probe;
    uint max_age;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.n) {
        return;
    }
    uint64_t key = U64Ptr(pc.keys).v[i];
    U64Ptr cells = U64Ptr(pc.cells);
    uint found = 0u;
    for (uint age = 1u; age <= pc.max_age; ++age) {
        uint slot = hash_slot(key, age, pc.probe, pc.table_size, pc.fastmod_m);
        if (atomicCompSwap(cells.v[slot], 0ul, key + 1ul) == 0ul) {
            found = age;
            break;
        }
    }
    U32Ptr(pc.ages).v[i] = found;
}
