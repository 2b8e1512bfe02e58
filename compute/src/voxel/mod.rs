//! Surface voxelization: the voxels of an R³ grid over the unit cube that a triangle mesh's
//! surface touches (exact triangle–box overlap, so the set is conservative and complete), as
//! sorted unique Morton keys, on the GPU ([`Voxelizer`]) and in plain Rust. Meshes are first
//! normalized into the unit cube (`Mesh::normalize_to_unit_cube`: the longest axis spans
//! [0, 1]); voxel (x, y, z) of a grid of resolution R covers [x/R, (x+1)/R] × … .
//!
//! Trilinear filtering needs more than the surface voxels: the *interpolation voxels* are the
//! eight corners of every interpolation cell (the cube between eight neighbouring voxel
//! centres) that the surface touches — the thesis' "thick layer" (Lefebvre, Fig. 4.4). The
//! interpolation cells are the voxel grid shifted by half a voxel ([`VoxelGrid::cells`]), so
//! the same voxelizer finds them.

mod error;
pub(crate) mod gpu;
mod grid;
pub(crate) mod key_sets;
pub(crate) mod keys;
mod surface_cpu;
mod triangle_box;

pub use error::VoxelError;
pub use gpu::Voxelizer;
pub use grid::{VoxelGrid, MAX_RESOLUTION};
pub use key_sets::{difference_cpu, union_cpu, KeySets};
pub use keys::{SortUnique, VoxelKeys};
pub use surface_cpu::{
    check_triangles, dilate_cells_cpu, grid_cells_cpu, interpolation_voxels_cpu, surface_voxels_cpu,
};
pub use triangle_box::triangle_box_overlap;
