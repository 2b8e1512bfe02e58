//! Plain-Rust lookups over any texel function, the references of every store's GLSL lookups:
//! the same footprints, clamping and "undefined" answer.

pub use crate::texel::unpack_rgba8;
use glam::{UVec3, Vec3, Vec4};

/// The voxel a nearest lookup at `pos` reads: floor(pos·R), clamped onto the grid.
pub fn nearest_voxel(pos: Vec3, resolution: u32) -> [u32; 3] {
    let r = resolution as f32;
    (pos * r)
        .floor()
        .clamp(Vec3::ZERO, Vec3::splat(r - 1.0))
        .as_uvec3()
        .to_array()
}

/// Nearest lookup: the texel of the voxel containing `pos`, or 0 where it is not stored.
pub fn nearest_cpu(texel: impl Fn([u32; 3]) -> Option<u32>, pos: Vec3, resolution: u32) -> u32 {
    texel(nearest_voxel(pos, resolution)).unwrap_or(0)
}

/// The 8 voxels and weights of a trilinear lookup at `pos`: samples sit at voxel centres, the
/// corners base + {0,1}³ of q = pos·R − 0.5 are clamped onto the grid (clamp to edge).
pub fn trilinear_footprint(pos: Vec3, resolution: u32) -> [([u32; 3], f32); 8] {
    let q = pos * resolution as f32 - 0.5;
    let base = q.floor();
    let f = q - base;
    let hi = resolution as i32 - 1;
    std::array::from_fn(|o| {
        let d = UVec3::new(o as u32 & 1, (o as u32 >> 1) & 1, o as u32 >> 2);
        let c = (base.as_ivec3() + d.as_ivec3()).clamp(glam::IVec3::ZERO, glam::IVec3::splat(hi));
        let w = (0..3)
            .map(|a| if d[a] == 1 { f[a] } else { 1.0 - f[a] })
            .product::<f32>();
        (c.as_uvec3().to_array(), w)
    })
}

/// Trilinear lookup: the weighted sum of the 8 footprint texels, absent ones counting as
/// (0, 0, 0, 0) — so alpha below 1 tells that part of the footprint was undefined.
pub fn trilinear_cpu(texel: impl Fn([u32; 3]) -> Option<u32>, pos: Vec3, resolution: u32) -> Vec4 {
    trilinear_footprint(pos, resolution)
        .iter()
        .map(|&(v, w)| unpack_rgba8(texel(v).unwrap_or(0)) * w)
        .sum()
}
