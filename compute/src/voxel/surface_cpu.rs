//! The plain-Rust voxelizers: for every triangle, every cell of its bounding box is tested with
//! the exact triangle–box overlap; the interpolation voxels are the corners of the touched
//! interpolation cells.

use super::error::VoxelError;
use super::grid::VoxelGrid;
use super::triangle_box::triangle_box_overlap;
use crate::hash::{morton_decode, morton_encode};
use glam::Vec3;

/// Sorted, unique Morton keys of the voxels of an `resolution`³ grid over the unit cube that the
/// triangles touch. Vertices must already lie in the unit cube (outside parts are clipped).
///
/// # Panics
/// On a vertex index out of range or a resolution outside 1..=[`super::MAX_RESOLUTION`]
/// (the GPU voxelizer reports both as errors; this is the reference for tests).
pub fn surface_voxels_cpu(positions: &[Vec3], triangles: &[[u32; 3]], resolution: u32) -> Vec<u64> {
    let grid = VoxelGrid::voxels(resolution).expect("resolution in range");
    grid_cells_cpu(positions, triangles, grid)
}

/// Sorted, unique Morton keys of the cells of `grid` that the triangles touch.
pub fn grid_cells_cpu(positions: &[Vec3], triangles: &[[u32; 3]], grid: VoxelGrid) -> Vec<u64> {
    let r = grid.resolution as f32;
    let n = grid.extent() as i64;
    let half = Vec3::splat(0.5 / r);
    let shift = grid.grid_shift();
    let offset = grid.center_offset();
    let mut keys = Vec::new();
    for tri in triangles {
        let t = [
            positions[tri[0] as usize],
            positions[tri[1] as usize],
            positions[tri[2] as usize],
        ];
        let lo = t[0].min(t[1]).min(t[2]);
        let hi = t[0].max(t[1]).max(t[2]);
        // Cells whose closed box can touch the bounding box.
        let first = |v: f32| ((v * r + shift).ceil() as i64 - 1).clamp(0, n - 1) as u32;
        let last = |v: f32| ((v * r + shift).floor() as i64).clamp(0, n - 1) as u32;
        for z in first(lo.z)..=last(hi.z) {
            for y in first(lo.y)..=last(hi.y) {
                for x in first(lo.x)..=last(hi.x) {
                    let center = (Vec3::new(x as f32, y as f32, z as f32) + offset) / r;
                    if triangle_box_overlap(center, half, t) {
                        keys.push(morton_encode([x, y, z], 3));
                    }
                }
            }
        }
    }
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// The voxels that trilinear filtering reads anywhere on the surface, as sorted unique Morton
/// keys of the `resolution`³ grid: the eight corner voxels of every interpolation cell the
/// surface touches (cell j spans the voxel centres j−1 and j per axis; corners outside the grid
/// are clamped onto it, as a clamp-to-edge lookup reads them).
///
/// # Panics
/// As [`surface_voxels_cpu`].
pub fn interpolation_voxels_cpu(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    resolution: u32,
) -> Vec<u64> {
    let grid = VoxelGrid::cells(resolution).expect("resolution in range");
    let cells = grid_cells_cpu(positions, triangles, grid);
    dilate_cells_cpu(&cells, resolution)
}

/// The clamped corner voxels of interpolation cells given as Morton keys of the shifted grid.
pub fn dilate_cells_cpu(cells: &[u64], resolution: u32) -> Vec<u64> {
    let mut keys = Vec::with_capacity(cells.len() * 8);
    for &c in cells {
        let j = morton_decode(c, 3);
        for o in 0..8u32 {
            let mut v = [0u32; 3];
            for a in 0..3 {
                let down = (o >> a) & 1;
                v[a] = (j[a] as i64 - down as i64).clamp(0, resolution as i64 - 1) as u32;
            }
            keys.push(morton_encode(v, 3));
        }
    }
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// Checks that every triangle names existing vertices.
pub fn check_triangles(positions: &[Vec3], triangles: &[[u32; 3]]) -> Result<(), VoxelError> {
    for (i, t) in triangles.iter().enumerate() {
        if let Some(&v) = t.iter().find(|&&v| v as usize >= positions.len()) {
            return Err(VoxelError::VertexIndex {
                triangle: i,
                vertex: v,
                vertices: positions.len(),
            });
        }
    }
    Ok(())
}
