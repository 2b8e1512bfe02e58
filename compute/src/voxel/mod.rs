//! Surface voxelization: the voxels of an R³ grid over the unit cube that a triangle mesh's
//! surface touches (exact triangle–box overlap, so the set is conservative and complete), as
//! sorted unique Morton keys. Meshes are first normalized into the unit cube
//! (`Mesh::normalize_to_unit_cube`: the longest axis spans [0, 1]); voxel (x, y, z) of a grid
//! of resolution R covers [x/R, (x+1)/R] × … .

mod surface_cpu;
mod triangle_box;

pub use surface_cpu::surface_voxels_cpu;
pub use triangle_box::triangle_box_overlap;
