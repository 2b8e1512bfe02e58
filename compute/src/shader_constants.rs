//! Constants shared by Rust and GLSL, defined once here.
//!
//! `build.rs` reads this file and passes every `pub const NAME: u32 = LITERAL;` line to the GLSL
//! compiler as `#define NAME VALUE`, so a kernel and its host code can never disagree on a tile
//! size or a digit width. Only plain `u32` literals are allowed on such lines.

/// Workgroup size used by every kernel unless its caller asks otherwise: lavapipe runs
/// workgroups of 256 invocations about twice as fast as workgroups of 32–64.
pub const DEFAULT_WORKGROUP_SIZE: u32 = 256;

/// Elements each invocation of the scan and reduce kernels owns (four `uvec4` loads).
pub const SCAN_ITEMS_PER_THREAD: u32 = 8;

/// Elements in one scan/reduce tile: `DEFAULT_WORKGROUP_SIZE * SCAN_ITEMS_PER_THREAD`.
pub const SCAN_TILE: u32 = 2048;

/// Bits of the key consumed by one radix-sort pass.
pub const RADIX_BITS: u32 = 8;

/// Buckets of one radix-sort pass: `1 << RADIX_BITS`.
pub const RADIX_BUCKETS: u32 = 256;

/// Keys each radix-sort invocation counts and scatters, about: fewer make the digit-major
/// histogram (every invocation's [`RADIX_BUCKETS`] counters, scanned each pass) dominate.
pub const RADIX_KEYS_PER_INVOCATION: u32 = 2048;

/// Reduce operator ids (a specialization constant of the reduce kernels).
pub const REDUCE_OP_SUM: u32 = 0;
/// See [`REDUCE_OP_SUM`].
pub const REDUCE_OP_MIN: u32 = 1;
/// See [`REDUCE_OP_SUM`].
pub const REDUCE_OP_MAX: u32 = 2;

/// Compaction modes: keep where a separate flag word is non-zero, or where the value itself
/// differs from a sentinel.
pub const COMPACT_BY_FLAGS: u32 = 0;
/// See [`COMPACT_BY_FLAGS`].
pub const COMPACT_BY_SENTINEL: u32 = 1;

const _: () = assert!(RADIX_BUCKETS == 1 << RADIX_BITS);

/// Largest probe age of the Robin Hood hashes: ages are stored in 4 bits, 0 meaning empty.
pub const HASH_MAX_AGE: u32 = 15;
/// Query result for an absent key (so payloads must be smaller).
pub const HASH_NOT_FOUND: u32 = 4294967295;
/// Probe sequences: coherent h_i(k) = k + o_i mod |H|, or randomizing.
pub const HASH_PROBE_COHERENT: u32 = 0;
/// See [`HASH_PROBE_COHERENT`].
pub const HASH_PROBE_RANDOM: u32 = 1;
/// Cuckoo hash functions are ((a k + b) mod CUCKOO_PRIME) mod |H| (Alcantara et al.).
pub const CUCKOO_PRIME: u32 = 4294967291;
/// Hash functions of the cuckoo table.
pub const CUCKOO_FUNCTIONS: u32 = 4;

/// The coherent probe offsets o_0 .. o_15 (o_0 = 0, then large fixed values), from García et
/// al.'s reference implementation; age a probes offset o_(a-1).
pub const COHERENT_OFFSET_0: u32 = 0;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_1: u32 = 3949349;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_2: u32 = 8984219;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_3: u32 = 9805709;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_4: u32 = 7732727;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_5: u32 = 1046459;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_6: u32 = 9883879;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_7: u32 = 4889399;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_8: u32 = 2914183;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_9: u32 = 3503623;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_10: u32 = 1734349;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_11: u32 = 8860463;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_12: u32 = 1326319;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_13: u32 = 1613597;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_14: u32 = 8604269;
/// See [`COHERENT_OFFSET_0`].
pub const COHERENT_OFFSET_15: u32 = 9647369;

/// The offsets as an array, for the CPU side.
pub const COHERENT_OFFSETS: [u32; 16] = [
    COHERENT_OFFSET_0,
    COHERENT_OFFSET_1,
    COHERENT_OFFSET_2,
    COHERENT_OFFSET_3,
    COHERENT_OFFSET_4,
    COHERENT_OFFSET_5,
    COHERENT_OFFSET_6,
    COHERENT_OFFSET_7,
    COHERENT_OFFSET_8,
    COHERENT_OFFSET_9,
    COHERENT_OFFSET_10,
    COHERENT_OFFSET_11,
    COHERENT_OFFSET_12,
    COHERENT_OFFSET_13,
    COHERENT_OFFSET_14,
    COHERENT_OFFSET_15,
];

/// Words of a TileTree leaf record (origin, depth and face mask; per face its tile's map corner
/// and rectangle): `store/tiletree.glsl` strides by it.
pub const TILETREE_LEAF_WORDS: u32 = 14;
/// Words of a TileTree tile record of the fill kernels (`store/tiletree_build.glsl`).
pub const TILETREE_TILE_WORDS: u32 = 12;

/// Key-set operations of `glsl/voxel/key_sets.comp` (`voxel::KeySets`): a ∪ b.
pub const KEY_SET_UNION: u32 = 0;
/// See [`KEY_SET_UNION`]: a \ b.
pub const KEY_SET_DIFFERENCE: u32 = 1;

/// Mode of the stores' lookup harnesses (`glsl/store/*_lookup.comp`) that writes a sample
/// lookup (`StoreSample` in `store/texels.glsl`): two vec4 per point, the trilinear (TileTree:
/// bilinear) sum, then (coverage, gradient of alpha). A high bit, so the octree's MIP modes
/// (2 + depth) stay free.
pub const STORE_LOOKUP_SAMPLE: u32 = 2147483648;

/// Fractional bits of a compressed tree's values (`ctree`): 1/64 of a grey level.
pub const CTREE_VALUE_FRAC_BITS: u32 = 6;
/// Fractional bits of a compressed-tree lookup position, in finest lattice spacings.
pub const CTREE_POS_FRAC_BITS: u32 = 8;
/// Fractional bits of a compressed-tree interpolation weight within a cell.
pub const CTREE_WEIGHT_BITS: u32 = 12;
/// Fractional bits of a compressed-tree level of detail.
pub const CTREE_LOD_FRAC_BITS: u32 = 8;
/// A compressed tree's indirection entry (or record address) for no subtree.
pub const CTREE_NO_SUBTREE: u32 = 4294967295;
/// Largest scaled offset of a compressed tree's pointer byte (7 bits).
pub const CTREE_MAX_OFFSET: u32 = 127;
/// Largest code magnitude of a compressed tree's residual (7 bits, kept symmetric).
pub const CTREE_MAX_CODE: u32 = 63;
/// Device addresses per level in the compressed-tree builder's level table: values, codes,
/// internal flags, block sizes, record addresses, records in preorder, the record count.
pub const CTREE_TABLE_WORDS: u32 = 7;
/// See [`CTREE_TABLE_WORDS`]: the level's reconstructed values (int).
pub const CTREE_TABLE_VALUES: u32 = 0;
/// See [`CTREE_TABLE_WORDS`]: the level's codes (int; residuals before quantization).
pub const CTREE_TABLE_CODES: u32 = 1;
/// See [`CTREE_TABLE_WORDS`]: 1 where a node has a live child.
pub const CTREE_TABLE_INTERNAL: u32 = 2;
/// See [`CTREE_TABLE_WORDS`]: block sizes (0 for nodes that are not internal).
pub const CTREE_TABLE_BLOCKS: u32 = 3;
/// See [`CTREE_TABLE_WORDS`]: byte addresses of the records ([`CTREE_NO_SUBTREE`] for none).
pub const CTREE_TABLE_ADDRESSES: u32 = 4;
/// See [`CTREE_TABLE_WORDS`]: the dense indices of the internal nodes in preorder.
pub const CTREE_TABLE_RECORDS: u32 = 5;
/// See [`CTREE_TABLE_WORDS`]: the word holding the record count.
pub const CTREE_TABLE_COUNT: u32 = 6;
/// uint64 statistics per level of the compressed-tree builder.
pub const CTREE_STATS_WORDS: u32 = 8;
/// See [`CTREE_STATS_WORDS`]: the largest residual magnitude.
pub const CTREE_STAT_MAX_RESIDUAL: u32 = 0;
/// See [`CTREE_STATS_WORDS`]: the level's step.
pub const CTREE_STAT_STEP: u32 = 1;
/// See [`CTREE_STATS_WORDS`]: the largest unpadded child offset, y_max.
pub const CTREE_STAT_MAX_OFFSET: u32 = 2;
/// See [`CTREE_STATS_WORDS`]: the best (padding << 32 | scale) of the scale search.
pub const CTREE_STAT_BEST: u32 = 3;
/// See [`CTREE_STATS_WORDS`]: the sum of the level's block sizes.
pub const CTREE_STAT_BLOCKS: u32 = 4;
/// Added to a candidate scale's padding total when one of its offsets does not fit 7 bits.
pub const CTREE_INFEASIBLE_SHIFT: u32 = 40;
/// `ctree::Border::Anchored` in the builder's push block.
pub const CTREE_BORDER_ANCHORED: u32 = 0;
/// `ctree::Border::Free` in the builder's push block.
pub const CTREE_BORDER_FREE: u32 = 1;
