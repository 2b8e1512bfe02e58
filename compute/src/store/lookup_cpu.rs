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

/// A sample lookup (`StoreSample` in `glsl/include/store/texels.glsl`): what a relief reads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StoreSample {
    /// The weighted sum the colour lookup returns.
    pub sum: Vec4,
    /// Total weight of the stored corners (alpha byte above 0): a store whose alpha carries a
    /// relief channel cannot tell coverage from alpha.
    pub coverage: f32,
    /// Gradient of `sum.w` with respect to the lookup position.
    pub gradient: Vec3,
}

/// The sample lookup over the trilinear footprint: the sum as [`trilinear_cpu`], the stored
/// corners' weight, and the analytic gradient of the alpha channel (each corner's weight
/// differentiated, `dq/dpos = R`).
pub fn trilinear_sample_cpu(
    texel: impl Fn([u32; 3]) -> Option<u32>,
    pos: Vec3,
    resolution: u32,
) -> StoreSample {
    let q = pos * resolution as f32 - 0.5;
    let f = q - q.floor();
    let r = resolution as f32;
    let mut s = StoreSample::default();
    for (o, (v, w)) in trilinear_footprint(pos, resolution).into_iter().enumerate() {
        let d = Vec3::new((o & 1) as f32, ((o >> 1) & 1) as f32, (o >> 2) as f32);
        let wa = Vec3::ONE - f + d * (2.0 * f - Vec3::ONE);
        let sign = (2.0 * d - Vec3::ONE) * r;
        let dw = Vec3::new(
            sign.x * wa.y * wa.z,
            wa.x * sign.y * wa.z,
            wa.x * wa.y * sign.z,
        );
        let t = texel(v).unwrap_or(0);
        let c = unpack_rgba8(t);
        s.sum += c * w;
        if t >> 24 != 0 {
            s.coverage += w;
        }
        s.gradient += dw * c.w;
    }
    s
}
