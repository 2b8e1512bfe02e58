//! Procedural solid textures (twin of `render/solid_texture.glsl`): the stores' integer marble
//! (`lazysolid_compute::store::marble_band_at`, exact on every device), and for wood, gradient
//! noise on an integer lattice whose gradients come from an integer hash, so no result depends
//! on how a device rounds a float hash.

use crate::shader_constants::{TEXTURE_MARBLE, TEXTURE_NONE, TEXTURE_WOOD};
use crate::shading::GpuMaterial;
use glam::{IVec3, Vec3};
use lazysolid_compute::store::{marble_band_at, MARBLE_BAND_ONE};
use std::f32::consts::TAU;

const WOOD_OCTAVES: u32 = 3;
/// Noise seed of the marble texture (`TEXTURE_MARBLE_SEED` in GLSL).
const MARBLE_SEED: u32 = 0;

fn mix32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

fn gradient(c: IVec3) -> Vec3 {
    let h = mix32(c.x as u32 ^ mix32(c.y as u32 ^ mix32(c.z as u32)));
    let field = |shift: u32| ((h >> shift) & 1023) as f32;
    Vec3::new(field(0), field(10), field(20)) * (2.0 / 1023.0) - Vec3::ONE
}

/// Gradient noise with quintic interpolation, 0 on lattice points.
pub fn texture_noise(p: Vec3) -> f32 {
    let fl = p.floor();
    let c = fl.as_ivec3();
    let r = p - fl;
    let w = r * r * r * (r * (r * 6.0 - Vec3::splat(15.0)) + Vec3::splat(10.0));
    let corner = |dx: i32, dy: i32, dz: i32| {
        let d = IVec3::new(dx, dy, dz);
        gradient(c + d).dot(r - d.as_vec3())
    };
    let lerp = |a: f32, b: f32, t: f32| a + t * (b - a);
    let x00 = lerp(corner(0, 0, 0), corner(1, 0, 0), w.x);
    let x10 = lerp(corner(0, 1, 0), corner(1, 1, 0), w.x);
    let x01 = lerp(corner(0, 0, 1), corner(1, 0, 1), w.x);
    let x11 = lerp(corner(0, 1, 1), corner(1, 1, 1), w.x);
    lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z)
}

fn fractal(mut p: Vec3, octaves: u32) -> f32 {
    let mut sum = 0.0;
    let mut amplitude = 1.0;
    for _ in 0..octaves {
        let n = texture_noise(p);
        sum += amplitude * n;
        p *= 2.0;
        amplitude *= 0.5;
    }
    sum
}

/// Weight of colour b at `p` already scaled to features (marble: b is the veins' colour).
fn blend(kind: u32, p: Vec3) -> f32 {
    match kind {
        TEXTURE_MARBLE => {
            1.0 - marble_band_at(p.to_array(), MARBLE_SEED) as f32 / MARBLE_BAND_ONE as f32
        }
        TEXTURE_WOOD => {
            let r = (p.x * p.x + p.z * p.z).sqrt() + 0.5 * fractal(p, WOOD_OCTAVES);
            let ring = 0.5 + 0.5 * (TAU * r).cos();
            ring * ring * (3.0 - 2.0 * ring)
        }
        _ => {
            let c = p.floor().as_ivec3();
            ((c.x + c.y + c.z) & 1) as f32
        }
    }
}

/// Albedo of `m` at the rest-pose object-space point `p_object` (`m.color` when untextured).
pub fn solid_texture_albedo(m: &GpuMaterial, p_object: Vec3) -> Vec3 {
    if m.texture_kind == TEXTURE_NONE {
        return m.color.into();
    }
    let t = blend(m.texture_kind, p_object * m.tex_scale);
    Vec3::from(m.tex_color_a) * (1.0 - t) + Vec3::from(m.tex_color_b) * t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shader_constants::TEXTURE_CHECKER;

    #[test]
    fn noise_vanishes_on_the_lattice_and_stays_bounded() {
        assert_eq!(texture_noise(Vec3::new(3.0, -2.0, 7.0)), 0.0);
        let mut max = 0.0f32;
        for i in 0..2000 {
            let p = Vec3::new(i as f32 * 0.137, i as f32 * 0.071 - 40.0, i as f32 * 0.013);
            max = max.max(texture_noise(p).abs());
        }
        assert!(max > 0.2 && max < 2.0, "{max}");
    }

    #[test]
    fn checker_alternates() {
        let m = GpuMaterial {
            texture_kind: TEXTURE_CHECKER,
            tex_color_a: [1.0; 3],
            tex_color_b: [0.0; 3],
            tex_scale: 2.0,
            ..Default::default()
        };
        assert_eq!(solid_texture_albedo(&m, Vec3::splat(0.1)), Vec3::ONE);
        assert_eq!(
            solid_texture_albedo(&m, Vec3::new(0.6, 0.1, 0.1)),
            Vec3::ZERO
        );
        assert_eq!(
            solid_texture_albedo(&m, Vec3::new(-0.1, 0.1, 0.1)),
            Vec3::ZERO
        );
    }
}
