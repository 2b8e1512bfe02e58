// Trilinear lookup in a blocked perfect hash (compute/src/hash/perfect/blocked.rs), usable from
// any kernel after "hash/perfect.glsl". Keys are blocks B of b×b×b interpolation cells (cell j
// spans the voxel centres j−1 and j, j in 0..=R); slot s holds (b+1)³ RGBA8 texels, texel
// t in [0, b]³ at word s·(b+1)³ + t.x + (b+1)·(t.y + (b+1)·t.z), the voxel clamp(B·b − 1 + t)
// (borders duplicated between neighbouring blocks). A footprint's cell j = floor(pos·R − 0.5)
// + 1 lies in block j / b at local j mod b, so its 8 texels are local + {0,1}³ of one block:
// one offset read, then 8 reads from one block.
#ifndef LAZYSOLID_HASH_PERFECT_BLOCKED_GLSL
#define LAZYSOLID_HASH_PERFECT_BLOCKED_GLSL

// The block of pos's footprint: the word of its slot's first texel, the footprint's local
// cell in the block and the trilinear fractions.
void perfect_blocked_footprint(PerfectHashParams p, uint block, uint resolution, vec3 pos, out uint base,
                               out uvec3 local, out vec3 f) {
    precise vec3 q = pos * float(resolution) - 0.5;
    vec3 fl = floor(q);
    f = q - fl;
    uvec3 j = uvec3(clamp(ivec3(fl) + 1, ivec3(0), ivec3(int(resolution))));
    uvec3 b = j / block;
    local = j - b * block;
    base = perfect_slot(p, b) * p.block_words;
}

// Corner o (bit 0: +x, bit 1: +y, bit 2: +z) of the footprint at local cell `local`.
uint perfect_blocked_texel(PerfectHashParams p, uint block, uint base, uvec3 local, int o) {
    uvec3 t = local + uvec3(o & 1, (o >> 1) & 1, o >> 2);
    uint side = block + 1u;
    return U32Ptr(p.data).v[base + t.x + side * (t.y + side * t.z)];
}

vec4 perfect_blocked_trilinear(PerfectHashParams p, uint block, uint resolution, vec3 pos) {
    uint base;
    uvec3 local;
    vec3 f;
    perfect_blocked_footprint(p, block, resolution, pos, base, local, f);
    vec4 sum = vec4(0.0);
    for (int o = 0; o < 8; ++o) {
        vec3 w3 = mix(1.0 - f, f, vec3(uvec3(o & 1, (o >> 1) & 1, o >> 2)));
        sum += (w3.x * w3.y * w3.z) * unpackUnorm4x8(perfect_blocked_texel(p, block, base, local, o));
    }
    return sum;
}

#endif
