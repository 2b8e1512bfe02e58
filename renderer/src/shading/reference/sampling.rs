//! Warps of the unit square and the local frame (twin of `render/sampling.glsl` and
//! `render/math.glsl`).

use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI, TAU};

/// The concentric map in polar form: signed radius, 1 − |radius| computed exactly from `u`, and
/// angle.
fn concentric_polar(u: Vec2) -> (f32, f32, f32) {
    let o = u * 2.0 - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        (0.0, 1.0, 0.0)
    } else if o.x.abs() > o.y.abs() {
        (o.x, 2.0 * u.x.min(1.0 - u.x), (0.25 * PI) * (o.y / o.x))
    } else {
        (
            o.y,
            2.0 * u.y.min(1.0 - u.y),
            0.5 * PI - (0.25 * PI) * (o.x / o.y),
        )
    }
}

/// Shirley–Chiu concentric map of the unit square onto the unit disc.
pub fn sample_concentric_disk(u: Vec2) -> Vec2 {
    let (r, _, theta) = concentric_polar(u);
    Vec2::new(r * theta.cos(), r * theta.sin())
}

/// Cosine-weighted direction about +z, with z = √((1 − r)(1 + r)) accurate near the horizon.
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let (r, one_minus_r, theta) = concentric_polar(u);
    Vec3::new(
        r * theta.cos(),
        r * theta.sin(),
        (one_minus_r * (2.0 - one_minus_r)).sqrt(),
    )
}

/// Density of [`sample_cosine_hemisphere`].
pub fn pdf_cosine_hemisphere(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform direction on the sphere (density 1 / 4π).
pub fn sample_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Right-handed orthonormal `(t, b)` completing the unit `n` (Duff et al. 2017).
pub fn make_frame(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let c = n.x * n.y * a;
    (
        Vec3::new(1.0 + s * n.x * n.x * a, s * c, -s * n.x),
        Vec3::new(c, s + n.y * n.y * a, -n.y),
    )
}
