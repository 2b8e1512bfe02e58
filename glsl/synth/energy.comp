#version 460
// Neighbourhood energy of a synthesized image: for each sampled output pixel, the smallest
// squared RGB distance between its 7x7 neighbourhood and any (toroidal) 7x7 neighbourhood of
// the exemplar, by exhaustive search (a candidate is abandoned once its partial sum reaches the
// best so far, which cannot change the minimum). CPU reference: synth/src/energy.rs.
#include "common.glsl"

#define R 3
#define SIDE (2 * R + 1)

layout(push_constant, scalar) uniform Push {
    uint64_t exemplar;   // packed RGB (r | g << 8 | b << 16) per exemplar pixel
    uint64_t image;      // packed RGB per output pixel
    uint64_t positions;  // sampled output positions, x | y << 16
    uint64_t energies;   // output: one minimum per sample
    uvec2 exemplar_size;
    uint image_width;
    uint samples;
    uint first;          // first exemplar pixel (linear index) searched by this dispatch
    uint end;
} pc;

void main() {
    uint i = uint(global_index());
    if (i >= pc.samples) {
        return;
    }
    uint pos = U32Ptr(pc.positions).v[i];
    uvec2 p = uvec2(pos & 0xffffu, pos >> 16);
    uint hood[SIDE * SIDE];
    for (int n = 0; n < SIDE * SIDE; n++) {
        uvec2 q = p + uvec2(n % SIDE, n / SIDE) - uvec2(R);
        hood[n] = U32Ptr(pc.image).v[q.y * pc.image_width + q.x];
    }
    uint best = pc.first == 0 ? 0xffffffffu : U32Ptr(pc.energies).v[i];
    for (uint u = pc.first; u < pc.end; u++) {
        uint ux = u % pc.exemplar_size.x;
        uint uy = u / pc.exemplar_size.x;
        uint d = 0;
        for (int n = 0; n < SIDE * SIDE && d < best; n++) {
            uint ex = (ux + pc.exemplar_size.x + uint(n % SIDE) - R) % pc.exemplar_size.x;
            uint ey = (uy + pc.exemplar_size.y + uint(n / SIDE) - R) % pc.exemplar_size.y;
            uint e = U32Ptr(pc.exemplar).v[ey * pc.exemplar_size.x + ex];
            for (int c = 0; c < 3; c++) {
                int diff = int(bitfieldExtract(hood[n], 8 * c, 8)) - int(bitfieldExtract(e, 8 * c, 8));
                d += uint(diff * diff);
            }
        }
        best = min(best, d);
    }
    U32Ptr(pc.energies).v[i] = best;
}
