//! Analytic area lights (twin of `render/lights.glsl`).

use super::sampling::make_frame;
use crate::shader_constants::LIGHT_SPHERE;
use crate::shading::GpuLight;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// A direction towards a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    /// Unit direction from the shading point.
    pub wi: Vec3,
    /// Distance to the sampled point.
    pub dist: f32,
    /// Radiance arriving along `wi`.
    pub radiance: Vec3,
    /// Solid-angle pdf at the shading point.
    pub pdf: f32,
}

/// Where a ray meets a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightHit {
    /// Ray parameter.
    pub t: f32,
    /// Radiance seen (0 on the back of a one-sided quad).
    pub radiance: Vec3,
}

/// 1 − cos θmax of the cone a sphere subtends.
fn cone(r2: f32, d2: f32) -> f32 {
    let s2 = r2 / d2;
    s2 / (1.0 + (1.0 - s2).max(0.0).sqrt())
}

/// Unit normal of a quad and the cosine at which `wi` (pointing at it) meets the emitting face.
fn quad_cosine(l: &GpuLight, wi: Vec3) -> f32 {
    let n = Vec3::from(l.u).cross(Vec3::from(l.v)) / l.area;
    let c = -wi.dot(n);
    if l.two_sided != 0 {
        c.abs()
    } else {
        c
    }
}

/// Samples a direction from `x` towards `l`; None inside a sphere, behind a one-sided quad.
pub fn light_sample(l: &GpuLight, x: Vec3, u: Vec2) -> Option<LightSample> {
    let radiance = Vec3::from(l.radiance);
    if l.kind == LIGHT_SPHERE {
        let to_c = Vec3::from(l.p) - x;
        let d2 = to_c.dot(to_c);
        let r2 = l.radius * l.radius;
        if d2 <= r2 {
            return None;
        }
        let d = d2.sqrt();
        let w = to_c / d;
        let cone = cone(r2, d2);
        let omc = u.x * cone;
        let cos_t = 1.0 - omc;
        let sin2_t = omc * (2.0 - omc);
        let sin_t = sin2_t.max(0.0).sqrt();
        let phi = TAU * u.y;
        let (t, b) = make_frame(w);
        let wi = ((sin_t * phi.cos()) * t + (sin_t * phi.sin()) * b + cos_t * w).normalize();
        let dist = d * cos_t - (r2 - d2 * sin2_t).max(0.0).sqrt();
        return (dist > 0.0).then_some(LightSample {
            wi,
            dist,
            radiance,
            pdf: 1.0 / (TAU * cone),
        });
    }
    let to_y = Vec3::from(l.p) + u.x * Vec3::from(l.u) + u.y * Vec3::from(l.v) - x;
    let dist2 = to_y.dot(to_y);
    if dist2 <= 0.0 {
        return None;
    }
    let dist = dist2.sqrt();
    let wi = to_y / dist;
    let cos_l = quad_cosine(l, wi);
    (cos_l > 0.0).then_some(LightSample {
        wi,
        dist,
        radiance,
        pdf: dist2 / (cos_l * l.area),
    })
}

/// Solid-angle pdf of [`light_sample`] from `x` producing `wi`, which hits `l` at `dist`.
pub fn light_pdf(l: &GpuLight, x: Vec3, wi: Vec3, dist: f32) -> f32 {
    if l.kind == LIGHT_SPHERE {
        let to_c = Vec3::from(l.p) - x;
        let d2 = to_c.dot(to_c);
        let r2 = l.radius * l.radius;
        return if d2 <= r2 {
            0.0
        } else {
            1.0 / (TAU * cone(r2, d2))
        };
    }
    let c = quad_cosine(l, wi);
    if c <= 0.0 {
        0.0
    } else {
        dist * dist / (c * l.area)
    }
}

/// First hit of `o + t d` (unit `d`) with `l` for t in (0, tmax).
pub fn light_intersect(l: &GpuLight, o: Vec3, d: Vec3, tmax: f32) -> Option<LightHit> {
    let p = Vec3::from(l.p);
    let t = if l.kind == LIGHT_SPHERE {
        let f = o - p;
        let b = f.dot(d);
        let perp = f - b * d;
        let disc = l.radius * l.radius - perp.dot(perp);
        if disc < 0.0 {
            return None;
        }
        let q = disc.sqrt();
        let near = -b - q;
        if near > 0.0 {
            near
        } else {
            -b + q
        }
    } else {
        let (u, v) = (Vec3::from(l.u), Vec3::from(l.v));
        let n = u.cross(v);
        let denom = n.dot(d);
        if denom == 0.0 {
            return None;
        }
        let t = (p - o).dot(n) / denom;
        let q = o + t * d - p;
        let w = n / n.dot(n);
        let a = w.dot(q.cross(v));
        let c = w.dot(u.cross(q));
        if !(0.0..=1.0).contains(&a) || !(0.0..=1.0).contains(&c) {
            return None;
        }
        t
    };
    if !(t > 0.0 && t < tmax) {
        return None;
    }
    let front = l.kind == LIGHT_SPHERE
        || l.two_sided != 0
        || Vec3::from(l.u).cross(Vec3::from(l.v)).dot(d) < 0.0;
    Some(LightHit {
        t,
        radiance: if front {
            Vec3::from(l.radiance)
        } else {
            Vec3::ZERO
        },
    })
}
