//! The plain-Rust surface voxelizer: for every triangle, every voxel of its bounding box is
//! tested with the exact triangle–box overlap.

use super::triangle_box::triangle_box_overlap;
use crate::hash::morton_encode;
use glam::Vec3;

/// Sorted, unique Morton keys of the voxels of an `resolution`³ grid over the unit cube that the
/// triangles touch. Vertices must already lie in the unit cube.
pub fn surface_voxels_cpu(positions: &[Vec3], triangles: &[[u32; 3]], resolution: u32) -> Vec<u64> {
    let r = resolution as f32;
    let half = Vec3::splat(0.5 / r);
    let mut keys = Vec::new();
    for tri in triangles {
        let t = [
            positions[tri[0] as usize],
            positions[tri[1] as usize],
            positions[tri[2] as usize],
        ];
        let lo = t[0].min(t[1]).min(t[2]);
        let hi = t[0].max(t[1]).max(t[2]);
        // Voxels whose closed box can touch the bounding box.
        let first = |v: f32| ((v * r).ceil() as i64 - 1).clamp(0, resolution as i64 - 1) as u32;
        let last = |v: f32| ((v * r).floor() as i64).clamp(0, resolution as i64 - 1) as u32;
        for z in first(lo.z)..=last(hi.z) {
            for y in first(lo.y)..=last(hi.y) {
                for x in first(lo.x)..=last(hi.x) {
                    let center = (Vec3::new(x as f32, y as f32, z as f32) + 0.5) / r;
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
