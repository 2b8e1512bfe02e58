//! Constants shared by Rust and GLSL, defined once here.
//!
//! `build.rs` reads this file and passes every `pub const NAME: u32 = VALUE;` line to the GLSL
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
