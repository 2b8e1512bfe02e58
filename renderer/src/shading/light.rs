//! The light record of the GPU (`Light` in `glsl/include/render/lights.glsl`).

use crate::scene::Light;
use crate::shader_constants::{LIGHT_QUAD, LIGHT_SPHERE};
use bytemuck::{Pod, Zeroable};

/// One analytic light as the kernels read it: scalar layout, field for field the GLSL struct.
/// Spheres use `p` and `radius`; quads `p`, `u`, `v` and `two_sided`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// Sphere centre or quad corner.
    pub p: [f32; 3],
    /// `LIGHT_*` of `shader_constants`.
    pub kind: u32,
    /// First edge of a quad.
    pub u: [f32; 3],
    /// Radius of a sphere.
    pub radius: f32,
    /// Second edge of a quad; a one-sided quad emits towards `u × v`.
    pub v: [f32; 3],
    /// Non-zero when a quad emits on both faces.
    pub two_sided: u32,
    /// Emitted radiance.
    pub radiance: [f32; 3],
    /// Surface area, precomputed so that sampling does not take a square root per sample.
    pub area: f32,
}

const _: () = assert!(size_of::<GpuLight>() == 64);

impl From<&Light> for GpuLight {
    fn from(light: &Light) -> Self {
        match *light {
            Light::Sphere {
                center,
                radius,
                radiance,
            } => GpuLight {
                p: center.to_array(),
                kind: LIGHT_SPHERE,
                radius,
                radiance: radiance.to_array(),
                area: 4.0 * std::f32::consts::PI * radius * radius,
                ..Default::default()
            },
            Light::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
                two_sided,
            } => GpuLight {
                p: corner.to_array(),
                kind: LIGHT_QUAD,
                u: edge_u.to_array(),
                v: edge_v.to_array(),
                two_sided: two_sided as u32,
                radiance: radiance.to_array(),
                area: edge_u.cross(edge_v).length(),
                radius: 0.0,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn quad_area_and_sidedness() {
        let g = GpuLight::from(&Light::Quad {
            corner: Vec3::ZERO,
            edge_u: Vec3::new(2.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 3.0),
            radiance: Vec3::ONE,
            two_sided: true,
        });
        assert_eq!((g.kind, g.two_sided, g.area), (LIGHT_QUAD, 1, 6.0));
        let s = GpuLight::from(&Light::Sphere {
            center: Vec3::ONE,
            radius: 0.5,
            radiance: Vec3::ONE,
        });
        assert_eq!((s.kind, s.radius, s.p), (LIGHT_SPHERE, 0.5, [1.0; 3]));
        assert_eq!(std::mem::offset_of!(GpuLight, radius), 28);
        assert_eq!(std::mem::offset_of!(GpuLight, two_sided), 44);
        assert_eq!(std::mem::offset_of!(GpuLight, area), 60);
    }
}
