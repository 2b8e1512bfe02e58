//! Compressed random-access trees (Lefebvre and Hoppe 2007; thesis §4.1.3): a 2D image or 3D
//! volume as a pruned primal tree of quantized prediction residuals, with the compact topology
//! of one byte per `PointerOrData` and a forested mipmap at the top. Made for smooth content
//! (light and occlusion bakes, distance fields, terrains, environment maps) that fixed-rate
//! block compression codes at the same rate everywhere. Layout, costs and measurements:
//! `docs/ctree.md`.
//!
//! - [`fields`]: smooth fields for tests and benchmarks (terrain, a torus' distance);
//! - [`lattice`]: the primal lattice and the slanted tree over it;
//! - [`residuals`]: hierarchical prediction, closed-loop quantization, pruning;
//! - [`pack`]: the compact topology, packed fine to coarse with per-level offset scales;
//! - [`tree`]: the forest and the assembled [`CompressedTree`];
//! - [`lookup`]: integer random access, the twin of the GLSL lookup;
//! - [`builder`]: the same tree built on the device from scan, sort and compaction;
//! - [`colour`]: RGB images as three trees of the YCoCg-R channels;
//! - [`device`]: the tree's buffers on a device and the record kernels read it through;
//! - [`mip_texture`]: the plain MIP texture that lookups are compared with;
//! - [`topology`]: the byte costs of the pointer, sibling and autumnal encodings beside it.

pub mod builder;
pub mod colour;
pub mod device;
mod error;
pub mod field;
pub mod fields;
pub mod lattice;
pub mod lookup;
pub mod mip_texture;
pub mod pack;
pub mod residuals;
pub mod topology;
pub mod tree;

pub use builder::{CtreeBuilder, DeviceBuildReport};
pub use device::{CtreeParams, DeviceTree, DownloadedTree, TimedCtreeLookup};
pub use error::CtreeError;
pub use field::ScalarField;
pub use lattice::Lattice;
pub use tree::{Border, CompressedTree, CtreeOptions, CtreeStats, LevelRow};

#[cfg(test)]
mod tests;
