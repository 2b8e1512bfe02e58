//! The material record of the GPU (`Material` in `glsl/include/render/material.glsl`).

use super::coat::{coat_terms, COAT_KNOTS};
use crate::scene::{Material, MaterialKind, SolidTextureKind};
use crate::shader_constants::{
    IMAGE_NONE, MATERIAL_CONDUCTOR, MATERIAL_DIELECTRIC, MATERIAL_EMISSIVE, MATERIAL_GLINT,
    MATERIAL_LAMBERTIAN, MATERIAL_PLASTIC, TEXTURE_CHECKER, TEXTURE_IMAGE, TEXTURE_MARBLE,
    TEXTURE_NONE, TEXTURE_WOOD,
};
use bytemuck::{Pod, Zeroable};

/// One material as the kernels read it: scalar layout, field for field the GLSL struct, so a
/// `&[GpuMaterial]` uploads as is.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Albedo (lambertian, plastic), η (conductor) or transmission tint (dielectric).
    pub color: [f32; 3],
    /// `MATERIAL_*` of `shader_constants`.
    pub kind: u32,
    /// Emitted radiance (emissive).
    pub emission: [f32; 3],
    /// GGX α = roughness².
    pub roughness: f32,
    /// Extinction κ of a conductor.
    pub k: [f32; 3],
    /// Index of refraction of a dielectric or of the plastic coat.
    pub ior: f32,
    /// First colour of the solid texture.
    pub tex_color_a: [f32; 3],
    /// `TEXTURE_*` of `shader_constants` (`TEXTURE_NONE`: the albedo is `color`).
    pub texture_kind: u32,
    /// Second colour of the solid texture.
    pub tex_color_b: [f32; 3],
    /// Solid texture features per unit of object space.
    pub tex_scale: f32,
    /// Plastic: the coat's directional albedo at the knots of [`coat_terms`].
    pub coat_albedo: [f32; COAT_KNOTS],
    /// Plastic: the share of the base's diffuse light that the coat reflects back down.
    pub coat_internal: f32,
    /// Glint: the index of its `GlintRecord` (`GLINT_NONE` for other kinds).
    pub glint: u32,
    /// The albedo image's record (`IMAGE_NONE` without one; `texture_kind` is then not
    /// `TEXTURE_IMAGE`).
    pub albedo_image: u32,
    /// The normal map's record (`IMAGE_NONE` without one).
    pub normal_image: u32,
}

const _: () = assert!(size_of::<GpuMaterial>() == 160);

impl GpuMaterial {
    /// The same material with the coat terms a plastic of its roughness and index needs
    /// (other kinds keep zeros): for records built field by field rather than from a scene
    /// material.
    pub fn with_coat(self) -> Self {
        if self.kind != MATERIAL_PLASTIC {
            return self;
        }
        let coat = coat_terms(self.roughness, self.ior);
        GpuMaterial {
            coat_albedo: coat.albedo,
            coat_internal: coat.internal,
            ..self
        }
    }
}

/// The GPU code of a material kind.
pub(crate) fn material_kind_code(kind: MaterialKind) -> u32 {
    match kind {
        MaterialKind::Lambertian => MATERIAL_LAMBERTIAN,
        MaterialKind::Conductor => MATERIAL_CONDUCTOR,
        MaterialKind::Plastic => MATERIAL_PLASTIC,
        MaterialKind::Dielectric => MATERIAL_DIELECTRIC,
        MaterialKind::Emissive => MATERIAL_EMISSIVE,
        MaterialKind::Glint => MATERIAL_GLINT,
    }
}

/// The GPU code of a solid texture kind.
pub(crate) fn texture_kind_code(kind: Option<SolidTextureKind>) -> u32 {
    match kind {
        None => TEXTURE_NONE,
        Some(SolidTextureKind::Marble) => TEXTURE_MARBLE,
        Some(SolidTextureKind::Wood) => TEXTURE_WOOD,
        Some(SolidTextureKind::Checker) => TEXTURE_CHECKER,
        // Read through its store only: the kernel never evaluates it (the flat colour, the
        // volume's mean, stands in if it ever did).
        Some(SolidTextureKind::Volume) => TEXTURE_NONE,
        Some(SolidTextureKind::Synthesized) => TEXTURE_NONE,
    }
}

impl From<&Material> for GpuMaterial {
    fn from(m: &Material) -> Self {
        let texture = m.texture.as_ref();
        GpuMaterial {
            color: m.color.to_array(),
            kind: material_kind_code(m.kind),
            emission: m.emission.to_array(),
            roughness: m.roughness,
            k: m.k.to_array(),
            ior: m.ior,
            tex_color_a: texture.map_or([0.0; 3], |t| t.color_a.to_array()),
            texture_kind: if m.albedo_map.is_some() {
                TEXTURE_IMAGE
            } else {
                texture_kind_code(texture.map(|t| t.kind))
            },
            tex_color_b: texture.map_or([0.0; 3], |t| t.color_b.to_array()),
            tex_scale: texture.map_or(0.0, |t| t.scale),
            glint: crate::shader_constants::GLINT_NONE,
            albedo_image: IMAGE_NONE,
            normal_image: IMAGE_NONE,
            ..Default::default()
        }
        .with_coat()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::SolidTexture;
    use glam::Vec3;

    #[test]
    fn fields_follow_the_scene_material() {
        let m = Material {
            name: "marble".into(),
            kind: MaterialKind::Plastic,
            color: Vec3::new(0.1, 0.2, 0.3),
            k: Vec3::ZERO,
            emission: Vec3::ZERO,
            roughness: 0.25,
            ior: 1.5,
            glint: None,
            albedo_map: None,
            normal_map: None,
            texture: Some(SolidTexture {
                kind: SolidTextureKind::Wood,
                color_a: Vec3::X,
                color_b: Vec3::Y,
                scale: 4.0,
                volume: None,
                synthesized: None,
                store: None,
            }),
        };
        let g = GpuMaterial::from(&m);
        assert_eq!(g.kind, MATERIAL_PLASTIC);
        assert_eq!(g.texture_kind, TEXTURE_WOOD);
        assert_eq!(g.color, [0.1, 0.2, 0.3]);
        assert_eq!(g.tex_color_b, [0.0, 1.0, 0.0]);
        assert_eq!(g.tex_scale, 4.0);
        assert_eq!(g.roughness, 0.25);
        assert_eq!(g.ior, 1.5);
        let plain = GpuMaterial::from(&Material { texture: None, ..m });
        assert_eq!(plain.texture_kind, TEXTURE_NONE);
        // Field offsets as GLSL's scalar layout places them.
        assert_eq!(std::mem::offset_of!(GpuMaterial, kind), 12);
        assert_eq!(std::mem::offset_of!(GpuMaterial, ior), 44);
        assert_eq!(std::mem::offset_of!(GpuMaterial, texture_kind), 60);
        assert_eq!(std::mem::offset_of!(GpuMaterial, tex_scale), 76);
        assert_eq!(std::mem::offset_of!(GpuMaterial, coat_internal), 144);
        assert_eq!(std::mem::offset_of!(GpuMaterial, normal_image), 156);
        assert_eq!(g.albedo_image, IMAGE_NONE);
        assert_eq!(g.coat_albedo, coat_terms(0.25, 1.5).albedo);
    }
}
