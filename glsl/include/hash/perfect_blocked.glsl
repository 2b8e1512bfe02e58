// Trilinear lookup in a blocked perfect hash (compute/src/hash/perfect/blocked.rs), usable from
// any kernel after "hash/perfect.glsl". Keys are blocks B of b×b×b interpolation cells (cell j
// spans the voxel centres j−1 and j, j in 0..=R); slot s holds (b+1)³ RGBA8 texels, texel
// t in [0, b]³ at word s·(b+1)³ + t.x + (b+1)·(t.y + (b+1)·t.z), the voxel clamp(B·b − 1 + t)
// (borders duplicated between neighbouring blocks). A footprint's cell j = floor(pos·R − 0.5)
// + 1 lies in block j / b at local j mod b, so its 8 texels are local + {0,1}³ of one block:
// one offset read, then 8 reads from one block.
#ifndef LAZYSOLID_HASH_PERFECT_BLOCKED_GLSL
#define LAZYSOLID_HASH_PERFECT_BLOCKED_GLSL

vec4 perfect_blocked_trilinear(PerfectHashParams p, uint block, uint resolution, vec3 pos) {
    precise vec3 q = pos * float(resolution) - 0.5;
    vec3 fl = floor(q);
    vec3 f = q - fl;
    uvec3 j = uvec3(clamp(ivec3(fl) + 1, ivec3(0), ivec3(int(resolution))));
    uvec3 b = j / block;
    uvec3 local = j - b * block;
    uint s = perfect_slot(p, b);
    uint side = block + 1u;
    U32Ptr data = U32Ptr(p.data);
    uint base = s * p.block_words;
    vec4 sum = vec4(0.0);
    for (int o = 0; o < 8; ++o) {
        uvec3 d = uvec3(o & 1, (o >> 1) & 1, o >> 2);
        uvec3 t = local + d;
        vec3 w3 = mix(1.0 - f, f, vec3(d));
        sum += (w3.x * w3.y * w3.z) * unpackUnorm4x8(data.v[base + t.x + side * (t.y + side * t.z)]);
    }
    return sum;
}

#endif
