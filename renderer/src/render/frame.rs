//! Per-render constants of the path-tracing kernel: the camera basis and the settings.

use crate::scene::{Camera, Lens, RenderSettings};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// The `Frame` block of `glsl/render/path_trace.comp` (scalar layout).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    /// Eye position.
    pub eye: [f32; 3],
    /// Aperture radius (0: pinhole).
    pub lens_radius: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// Distance in focus along `forward`.
    pub focus_distance: f32,
    /// Right vector scaled by tan(fov/2)·aspect.
    pub right: [f32; 3],
    /// Image width.
    pub width: u32,
    /// Up vector scaled by tan(fov/2).
    pub up: [f32; 3],
    /// Image height.
    pub height: u32,
    /// Seed of the random numbers.
    pub seed: u32,
    /// Maximum bounces.
    pub max_depth: u32,
    /// First depth of Russian roulette.
    pub rr_depth: u32,
    /// Number of analytic lights.
    pub light_count: u32,
    /// 1 when the environment is sampled by next-event estimation.
    pub env_sampled: u32,
    /// 1 when the pass writes the AOVs.
    pub aovs: u32,
    /// Unused.
    pub pad: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<GpuFrame>() == 96);

impl GpuFrame {
    /// The frame of `camera` rendered with `settings`.
    pub fn new(
        camera: &Camera,
        settings: &RenderSettings,
        light_count: u32,
        env_sampled: bool,
    ) -> GpuFrame {
        let forward = (camera.look_at - camera.position).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let tan_half = (camera.fov_y_deg.to_radians() * 0.5).tan();
        let aspect = settings.width as f32 / settings.height as f32;
        let (lens_radius, focus_distance) = match camera.lens {
            Lens::Pinhole => (0.0, 1.0),
            Lens::ThinLens {
                aperture_radius,
                focus_distance,
            } => (aperture_radius, focus_distance),
        };
        GpuFrame {
            eye: camera.position.into(),
            lens_radius,
            forward: forward.into(),
            focus_distance,
            right: (right * tan_half * aspect).into(),
            width: settings.width,
            up: (up * tan_half).into(),
            height: settings.height,
            seed: settings.seed,
            max_depth: settings.max_depth,
            rr_depth: settings.rr_depth,
            light_count,
            env_sampled: env_sampled as u32,
            aovs: 0,
            pad: [0; 2],
        }
    }

    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        Vec3::from(self.forward)
    }
}
