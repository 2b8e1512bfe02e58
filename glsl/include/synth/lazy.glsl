// Lazy solid synthesis state on the GPU (synth/src/solid/lazy/gpu/mod.rs): per level a
// coherent Robin Hood table from the voxel's Morton key (its absolute position plus a margin)
// to a slot, and per slot the versions computed so far (version j: the triple after pass j,
// 0 the upsampled one) and their count. The host keeps one LazyLevel record per level in a
// buffer; the kernels receive its address and the level.
#ifndef LAZYSOLID_LAZY_GLSL
#define LAZYSOLID_LAZY_GLSL

#define CELL_BITS 64
#include "morton.glsl"
#include "hash/robin_hood_lookup.glsl"

// Must match `LazyLevelRecord` in synth/src/solid/lazy/gpu/mod.rs (scalar layout, 60 bytes).
struct LazyLevel {
    uint64_t cells;        // the table's cells (unused while table_size is 0)
    uint64_t fastmod_m;    // the table size's reciprocal
    uint64_t versions;     // stride x 3 words per slot
    uint64_t counts;       // versions computed per slot
    uint table_size;       // 0 before the level's first voxel
    uint key_bits;         // bits of key + 1 in a cell
    uint probe;            // HASH_PROBE_COHERENT
    uint stride;           // versions per slot: the level's passes + 1
    int margin;            // added to positions before the Morton key
    uint extent;           // table positions lie in [0, extent) per axis
    uint parallel;         // 1: every stage corrects every voxel (synth/src/solid/schedule.rs)
};

layout(buffer_reference, scalar, buffer_reference_align = 8) buffer LazyLevels { LazyLevel v[]; };

// The bias of a lazy key (synth/src/solid/lazy/keys.rs; LAZY_AXIS_BITS from
// synth/src/shader_constants.rs).
const int LAZY_BIAS_GLSL = 1 << (LAZY_AXIS_BITS - 1u);

// Low bits of a stage-tagged key: tagged = key << LAZY_STAGE_BITS | (LAZY_STAGE_MAX - stage).
const uint LAZY_STAGE_BITS = 64u - 3u * LAZY_AXIS_BITS;
const uint LAZY_STAGE_MAX = (1u << LAZY_STAGE_BITS) - 1u;

// The key of no voxel: a voxel with nothing to request above it has it as its parent. It sorts
// after every real key, and the walk's unique pass drops it.
const uint64_t LAZY_NO_KEY = (1ul << (3u * LAZY_AXIS_BITS)) - 1ul;

// Workgroup counts (x, y, 1) of an indirect dispatch of `width`-wide workgroups over `count`
// invocations, folded into y past 65535 as Kernel::groups_for folds them (0: runs nothing).
uvec3 lazy_groups(uint count, uint width) {
    uint blocks = (count + width - 1u) / width;
    uint x = min(blocks, 65535u);
    uint y = x == 0u ? 1u : (blocks + x - 1u) / x;
    return uvec3(x, y, 1u);
}

uint64_t lazy_untag_key(uint64_t t) {
    return t >> LAZY_STAGE_BITS;
}

uint lazy_untag_stage(uint64_t t) {
    return LAZY_STAGE_MAX - uint(t & uint64_t(LAZY_STAGE_MAX));
}

uint64_t lazy_tag(uint64_t k, uint stage) {
    return (k << LAZY_STAGE_BITS) | uint64_t(LAZY_STAGE_MAX - stage);
}

// The absolute position of lazy key k.
ivec3 lazy_position(uint64_t k) {
    return ivec3(morton3_decode(k)) - LAZY_BIAS_GLSL;
}

// The lazy key of absolute position p.
uint64_t lazy_key(ivec3 p) {
    return morton3(uvec3(p + LAZY_BIAS_GLSL));
}

// Whether p lies where the level's table can hold it.
bool lazy_inside(LazyLevel l, ivec3 p) {
    uvec3 q = uvec3(p + l.margin);
    return all(lessThan(q, uvec3(l.extent)));
}

// The table key of absolute position p.
uint64_t lazy_table_key(LazyLevel l, ivec3 p) {
    return morton3(uvec3(p + l.margin));
}

// The slot of position p, or HASH_NOT_FOUND.
uint lazy_slot(LazyLevel l, ivec3 p) {
    if (l.table_size == 0u || !lazy_inside(l, p)) {
        return HASH_NOT_FOUND;
    }
    return robin_hood_lookup(l.cells, l.table_size, l.fastmod_m, l.key_bits, l.probe, lazy_table_key(l, p));
}

// Versions of position p computed so far (0 when it is not stored).
uint lazy_known(LazyLevel l, ivec3 p) {
    uint s = lazy_slot(l, p);
    return s == HASH_NOT_FOUND ? 0u : U32Ptr(l.counts).v[s];
}

// Version v of slot s.
uvec3 lazy_version(LazyLevel l, uint s, uint v) {
    uint w = (s * l.stride + v) * 3u;
    return uvec3(U32Ptr(l.versions).v[w], U32Ptr(l.versions).v[w + 1u], U32Ptr(l.versions).v[w + 2u]);
}

void lazy_store(LazyLevel l, uint s, uint v, uvec3 t) {
    uint w = (s * l.stride + v) * 3u;
    U32Ptr(l.versions).v[w] = t.x;
    U32Ptr(l.versions).v[w + 1u] = t.y;
    U32Ptr(l.versions).v[w + 2u] = t.z;
}

// The place of p's parity class in the subpass order (CLASSES_3D, a Gray code with x fastest).
uint lazy_class(ivec3 p) {
    uint x = uint(p.x & 1), y = uint(p.y & 1), z = uint(p.z & 1);
    uint g = x | (y << 1) | (z << 2);
    // Inverse of the reflected Gray code: g ^ (g >> 1) ^ (g >> 2).
    return g ^ (g >> 1u) ^ (g >> 2u);
}

// The first stage at which a needed voxel of level l is stored: 1, so that a voxel read only
// as upsampled (needed at stage 0) is computed in place by its readers instead; 0 on a level
// without passes, whose requested voxels are needed at stage 0.
uint lazy_store_from(LazyLevel l) {
    return l.stride == 1u ? 0u : 1u;
}

// Marks a stage that corrects every class (ALL_CLASSES in synth/src/solid/schedule.rs).
const uint LAZY_ALL_CLASSES = 8u;

// The version a voxel of class place `c` of level l holds after stage `stage`.
uint lazy_version_at(LazyLevel l, uint stage, uint c) {
    return l.parallel != 0u ? stage : (stage + 7u - c) >> 3;
}

// The key lazy_correct.comp's visiting order is sorted on (lazy_prepare.comp, LAZY_ORDER_BITS
// bits): one for a voxel without work (last), three for its class, six for the stage it is
// needed at, latest first (stages past 63 share the last place).
uint lazy_order_key(uint idle, uint cls, uint stage) {
    return (idle << 9) | (cls << 6) | (63u - min(stage, 63u));
}

// Whether a stage that corrects class place `cls` (or LAZY_ALL_CLASSES) corrects class `c`.
bool lazy_corrects(uint cls, uint c) {
    return cls == LAZY_ALL_CLASSES || cls == c;
}

#endif

