//! GGX with height-correlated Smith masking and visible-normal sampling (twin of
//! `render/microfacet.glsl`).

use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// Below this α a lobe is a delta (perfect mirror or smooth interface).
pub const GGX_MIN_ALPHA: f32 = 1e-3;

/// Distribution of normals D(m).
pub fn ggx_d(m: Vec3, alpha: f32) -> f32 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let t = m.x * m.x + m.y * m.y + a2 * m.z * m.z;
    a2 / (PI * t * t)
}

fn lambda(w: Vec3, alpha: f32) -> f32 {
    let t2 = alpha * alpha * (w.x * w.x + w.y * w.y) / (w.z * w.z);
    0.5 * t2 / (1.0 + (1.0 + t2).sqrt())
}

/// Smith masking of one direction.
pub fn ggx_g1(w: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(w, alpha))
}

/// Height-correlated masking-shadowing.
pub fn ggx_g2(wo: Vec3, wi: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(wo, alpha) + lambda(wi, alpha))
}

/// A normal distributed as the normals visible from `wo` (`wo.z > 0`), Heitz 2018.
pub fn ggx_sample_vndf(wo: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = TAU * u.y;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * (r * phi.sin());
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(0.0)).normalize()
}

/// Density of [`ggx_sample_vndf`].
pub fn ggx_vndf_pdf(wo: Vec3, m: Vec3, alpha: f32) -> f32 {
    ggx_g1(wo, alpha) * wo.dot(m).max(0.0) * ggx_d(m, alpha) / wo.z
}
