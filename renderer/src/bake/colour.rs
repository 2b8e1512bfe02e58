//! The colours a store gets from a texture that is not synthesized: a procedural pattern or a
//! volume read from a file, per voxel, as the sRGB-encoded RGBA8 words every store holds.

use crate::output::encode8;
use crate::scene::Material;
use crate::shading::reference::solid_texture_albedo;
use crate::shading::GpuMaterial;
use glam::Vec3;

/// sRGB-encoded RGBA8 (alpha 255) of a linear albedo: 8 bits per channel spent where the eye
/// sees differences, decoded in the kernel.
fn pack_srgb8(albedo: Vec3) -> u32 {
    let [r, g, b] = albedo.to_array().map(|v| encode8(v) as u32);
    r | g << 8 | b << 16 | 255 << 24
}

/// The colour of a procedural (or volume) texture at voxel `v` of a grid of resolution `r`,
/// as sRGB-encoded RGBA8.
pub(super) fn procedural_colour(material: &Material, r: u32) -> impl Fn([u32; 3]) -> u32 + Sync {
    let gm = GpuMaterial::from(material);
    let volume = material.texture.as_ref().and_then(|t| t.volume.clone());
    move |v: [u32; 3]| match &volume {
        // Already sRGB bytes.
        Some(volume) => {
            let [r_, g, b] = volume.at_voxel(v, r).map(|c| c as u32);
            r_ | g << 8 | b << 16 | 255 << 24
        }
        None => {
            let centre = (Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32) + 0.5) / r as f32;
            pack_srgb8(solid_texture_albedo(&gm, centre))
        }
    }
}
