//! Constants shared by the synthesizer's Rust and GLSL, defined once here.
//!
//! `build.rs` reads this file (and `lazysolid-compute`'s, whose hash constants the lazy kernels
//! use) and passes every `pub const NAME: u32 = LITERAL;` line to the GLSL compiler as
//! `#define NAME VALUE`, so a kernel and its host code can never disagree. Only plain `u32`
//! literals are allowed on such lines.

/// Coordinate tolerance, in exemplar pixels, of the synthesizer's period penalty
/// (`period.rs`): the period repetition measure's tolerance.
pub const SYNTH_PERIOD_TOLERANCE: u32 = 4;

/// Multiscale synthesis (`multiscale/`): level field of a magnified pixel, beyond every
/// finest level.
pub const MULTISCALE_MAGNIFIED: u32 = 255;
/// Largest magnitude of a cumulative transfer component, in 1/16 colour levels: one full colour
/// range (255 · 16), so every transfer fits 16 bits.
pub const MULTISCALE_MAX_TRANSFER: u32 = 4080;
/// Largest magnitude of a transfer's move of one appearance component.
pub const MULTISCALE_MAX_OFFSET_MOVE: u32 = 512;
/// Fixed-point bits of a transfer's move: the offset matrix's 8 plus the transfer's 4.
pub const MULTISCALE_OFFSET_MOVE_SHIFT: u32 = 12;
/// Lookup slots per exemplar in a depth set's packed layout (levels `0..=L`, `L ≤ 8`).
pub const MULTISCALE_LEVEL_SLOTS: u32 = 16;
/// Texel index of a pixel whose stack level is not in the depth set.
pub const MULTISCALE_ABSENT: u32 = 4294967295;
/// Flag of a working texel index whose pixel is not corrected (1 << 31).
pub const MULTISCALE_FIXED: u32 = 2147483648;
/// Flag of a candidate texel index (and of a level's lookup entry) whose level offers
/// candidates the period test can penalize (1 << 31).
pub const MULTISCALE_OFFERS_PERIOD: u32 = 2147483648;
/// Control words per depth of the multiscale correction (kernel choice on the device).
pub const MULTISCALE_CONTROL_WORDS: u32 = 8;

/// Largest S of solid-synthesis candidates: strips kept per other exemplar (the thesis' 65).
pub const SOLID_MAX_S: u32 = 65;
/// Triples kept per exemplar pixel after the crossbar ranking (the thesis' 100).
pub const SOLID_KEPT: u32 = 100;
/// Candidate triples per exemplar pixel after the coherence filter (the thesis' 12).
pub const SOLID_MAX_CANDIDATES: u32 = 12;
/// Longest crossbar strip: the crossbar ranking loops over S² pairs of N samples, and llvmpipe
/// stops an invocation after 65535 loop iterations in all (65² · (11 + 1) ≈ 51 k).
pub const SOLID_MAX_STRIP: u32 = 11;

/// Bits per axis of a lazy key's position (`solid/lazy/keys.rs`); the stage tag takes the
/// remaining `64 − 3 · 19` low bits of a tagged key.
pub const LAZY_AXIS_BITS: u32 = 19;

/// Words of the dependency walk's device counters (`solid/lazy/walk.rs`): the last scan's
/// total, which the scan writes to word 0.
pub const LAZY_WALK_TOTAL: u32 = 0;
/// Walk counter: 1 when a set outgrew its buffer (the walk runs again with larger ones).
pub const LAZY_WALK_OVERFLOW: u32 = 1;
/// Walk counter: the expanded set's length (kept and new entries) of the current stage.
pub const LAZY_WALK_EXPANDED: u32 = 2;
/// Walk counter: how many entries the current stage's sort orders (0 when nothing expanded:
/// the kept entries are sorted already).
pub const LAZY_WALK_SORTED: u32 = 3;
/// Walk counter: the entries of the current stage that expanded (`lazy_deps_expand.comp`
/// counts them atomically, `lazy_walk_step.comp` reads and resets it).
pub const LAZY_WALK_GROWN: u32 = 4;
/// The first walk counter the kernels do not name (the rest are laid out by `walk.rs`).
pub const LAZY_WALK_FIRST_FREE: u32 = 5;

/// Bits of the key lazy synthesis sorts a level's voxels on before its correction
/// (`lazy_order_key` in `synth/lazy.glsl`): a voxel without work, its class, its last stage.
pub const LAZY_ORDER_BITS: u32 = 10;

/// Words per stage of lazy synthesis's stage ranges (`lazy_stage_ranges.comp`): the indirect
/// workgroup counts x, y, z of the stage's correction, the stretch's first place and length.
pub const LAZY_RANGE_WORDS: u32 = 5;
