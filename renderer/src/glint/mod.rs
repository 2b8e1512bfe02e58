//! Glinting microstructure by example ("Example-Based Microstructure Rendering with Constant
//! Storage"): an infinite, non-repeating normal map blended from a small example, with O(1)
//! point queries (normal and Jacobian) and O(1) range min/max queries over power-of-two target
//! squares. See `docs/glints.md` for what is built and what is not yet.
//!
//! - [`example`]: the example normal map (from normals or a height field), bilinearly read.
//! - [`gaussianize`]: the Gaussianization tables of histogram-preserving blending.
//! - [`by_example`]: the point query (CPU twin of `glsl/include/glint/by_example.glsl`).
//! - [`range_table`]: the square-only sparse table over the example, 16-bit quantized.
//! - [`gpu_range_table`]: its device build, one dispatch per level.
//! - [`minmax_mip`]: the range table's baselines (a min–max mip hierarchy, brute force) and
//!   random query batches, for `lazysolid bench glints`.
//! - [`gpu_range_query`]: their device twins: the mip's build and query batches by any method.
//! - [`range_blend`]: conservative intervals of the blended map over a target square.
//! - [`gpu_map`]: the device record of a map (example, tables, parameters).
//! - [`timing`]: the glint scene rendered pruned, explicit and as the plain conductor, timed.
//! - [`gpu_material`]: the device records of a scene's glint materials.
//! - [`pndf`]: the P-NDF of a footprint (pruned traversal, the explicit reference) and its
//!   importance sampling.
//! - [`synthetic`]: a generated bumps-and-scratches height field for examples.

pub mod by_example;
pub mod error;
pub mod example;
pub mod gaussianize;
pub mod gpu_map;
pub mod gpu_material;
pub mod gpu_range_query;
pub mod gpu_range_table;
pub mod minmax_mip;
pub mod pndf;
pub mod range_blend;
pub mod range_table;
pub mod synthetic;
pub mod timing;

pub use by_example::{BlendMode, ByExampleMap, PointQuery};
pub use error::GlintError;
pub use example::NormalExample;
pub use gaussianize::GaussianTables;
pub use gpu_map::{GlintMapParams, GpuGlintMap};
pub use gpu_material::{GlintRecordParams, SceneGlints};
pub use gpu_range_query::{
    record_range_queries, GlintMinMaxMipPush, GlintRangeQueryPush, GpuMinMaxMip, RangeMethod,
};
pub use gpu_range_table::{build_range_table, record_range_table, GlintRangeLevelPush};
pub use minmax_mip::{random_squares, MinMaxMip, RangeSquare};
pub use pndf::{Footprint, MaterializedMap, PndfStats, SampleTexels};
pub use range_table::{NormalInterval, RangeTable};
pub use timing::{render_glint_cases, GlintCase, GlintTiming};
