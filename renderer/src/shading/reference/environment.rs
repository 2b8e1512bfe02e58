//! Environment evaluation and importance sampling (twin of `render/environment.glsl`, which
//! documents the lat-long convention).

use super::sampling::sample_uniform_sphere;
use crate::shader_constants::ENVIRONMENT_CONSTANT;
use crate::shading::EnvironmentMap;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI, TAU};

/// A sampled environment direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvSample {
    /// Unit world direction.
    pub dir: Vec3,
    /// Radiance from it.
    pub radiance: Vec3,
    /// Solid-angle pdf.
    pub pdf: f32,
}

fn to_world(e: &EnvironmentMap, m: Vec3) -> Vec3 {
    let (c, s) = (e.rotation_cos, e.rotation_sin);
    Vec3::new(c * m.x + s * m.z, m.y, -s * m.x + c * m.z)
}

fn to_map(e: &EnvironmentMap, w: Vec3) -> Vec3 {
    let (c, s) = (e.rotation_cos, e.rotation_sin);
    Vec3::new(c * w.x - s * w.z, w.y, s * w.x + c * w.z)
}

/// (column, row, sin θ) of a world direction.
fn texel_of(e: &EnvironmentMap, dir: Vec3) -> (u32, u32, f32) {
    let m = to_map(e, dir);
    let sin_theta = (m.x * m.x + m.z * m.z).sqrt();
    let mut phi = m.x.atan2(-m.z);
    if phi < 0.0 {
        phi += TAU;
    }
    let theta = m.y.clamp(-1.0, 1.0).acos();
    let col = ((phi * (1.0 / TAU) * e.width as f32) as u32).min(e.width - 1);
    let row = ((theta * FRAC_1_PI * e.height as f32) as u32).min(e.height - 1);
    (col, row, sin_theta)
}

fn texel_radiance(e: &EnvironmentMap, col: u32, row: u32) -> Vec3 {
    let i = 3 * (row * e.width + col) as usize;
    e.intensity * Vec3::new(e.texels[i], e.texels[i + 1], e.texels[i + 2])
}

/// Radiance from unit world direction `dir`.
pub fn env_eval(e: &EnvironmentMap, dir: Vec3) -> Vec3 {
    if e.kind == ENVIRONMENT_CONSTANT {
        return e.radiance;
    }
    let (col, row, _) = texel_of(e, dir);
    texel_radiance(e, col, row)
}

/// Solid-angle density of [`env_sample`] producing `dir`.
pub fn env_pdf(e: &EnvironmentMap, dir: Vec3) -> f32 {
    if !e.sampleable {
        return 0.0;
    }
    if e.kind == ENVIRONMENT_CONSTANT {
        return 0.25 * FRAC_1_PI;
    }
    let (col, row, sin_theta) = texel_of(e, dir);
    if sin_theta <= 0.0 {
        return 0.0;
    }
    e.pdf[(row * e.width + col) as usize] / (2.0 * PI * PI * sin_theta)
}

/// Largest i with `cdf[i] <= u`, i <= len - 2.
fn find_interval(cdf: &[f32], u: f32) -> usize {
    // cdf is sorted with cdf[0] = 0 <= u < 1 = cdf[last].
    cdf.partition_point(|&c| c <= u).clamp(1, cdf.len() - 1) - 1
}

/// Samples a direction proportionally to luminance × solid angle (uniformly for a constant).
pub fn env_sample(e: &EnvironmentMap, u: Vec2) -> Option<EnvSample> {
    if !e.sampleable {
        return None;
    }
    if e.kind == ENVIRONMENT_CONSTANT {
        return Some(EnvSample {
            dir: sample_uniform_sphere(u),
            radiance: e.radiance,
            pdf: 0.25 * FRAC_1_PI,
        });
    }
    let (w, h) = (e.width as usize, e.height as usize);
    let row = find_interval(&e.marginal_cdf, u.y);
    let dv = (u.y - e.marginal_cdf[row]) / (e.marginal_cdf[row + 1] - e.marginal_cdf[row]);
    let cdf = &e.conditional_cdf[row * (w + 1)..(row + 1) * (w + 1)];
    let col = find_interval(cdf, u.x);
    let du = (u.x - cdf[col]) / (cdf[col + 1] - cdf[col]);
    let theta = (row as f32 + dv) / h as f32 * PI;
    let phi = (col as f32 + du) / w as f32 * TAU;
    let sin_theta = theta.sin();
    if sin_theta <= 0.0 {
        return None;
    }
    let dir = to_world(
        e,
        Vec3::new(sin_theta * phi.sin(), theta.cos(), -sin_theta * phi.cos()),
    );
    let pdf = e.pdf[row * w + col] / (2.0 * PI * PI * sin_theta);
    (pdf > 0.0).then(|| EnvSample {
        dir,
        radiance: texel_radiance(e, col as u32, row as u32),
        pdf,
    })
}
