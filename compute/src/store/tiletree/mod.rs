//! The TileTree store (Lefebvre and Dachsbacher, "TileTrees", I3D 2007): an octree around the
//! surface, refined until each leaf holds at most one surface fold along the main axes, whose
//! leaves carry 2D texture tiles on up to six faces (each cropped to the surface it carries),
//! packed into one 2D tile map. A lookup descends to the leaf, picks the face from the surface
//! normal, projects the point in parallel onto it and does one bilinear fetch: 4 texels instead of the 8 of a volume's
//! trilinear filter, and only a surface layer of texels instead of a thick one.
//!
//! Split of the build: the CPU refines the tree (a recursive fold test per node), packs the
//! tiles and lists per tile the triangles its texels may hit ([`Plan`]); the GPU fills every
//! texel, borders included — surface hit, colour, dilation, copy into the map
//! ([`fill_cpu`] is the reference). Layout and lookup: `glsl/include/store/tiletree.glsl`;
//! design, limits and measurements: `docs/stores.md`.

mod config;
mod fill_cpu;
mod geometry;
pub(crate) mod gpu;
mod lookup_cpu;
mod pack;
mod plan;
mod refine;

pub use config::{TileTreeConfig, MAX_MAP_SIDE, MAX_MAP_TEXELS, MAX_TILE};
pub use fill_cpu::{fill_cpu, texel_voxel};
pub use geometry::{
    column_hit, dominant_face, Surface, CONE, FOLD_TOLERANCE, MARGIN, SWITCH_MARGIN,
};
pub use gpu::{TileTree, TileTreeParams};
pub use lookup_cpu::{descend, lookup_cpu, pick_face, sample_cpu, TileTreeHost};
pub use plan::{Plan, Tile, TileTreeStats, LEAF_WORDS, TILE_WORDS};
pub use refine::{Leaf, LEAF_BIT};

/// The store's name in messages, GLSL include and function names.
pub(crate) const NAME: &str = "tiletree";
