//! `[[material]]` tables: which keys each kind needs and accepts, the measured metal presets,
//! and solid textures.
//!
//! [`resolve`] reads one table and builds its [`Material`], kind by kind; the Lambertian,
//! plastic, dielectric and emissive kinds need nothing beyond it. Everything with rules of its
//! own lives in a file of its own:
//!
//! - [`fields`](mod@fields): the checks every kind shares: which keys each kind accepts, kind
//!   names for messages, and files that must exist.
//! - [`albedo`](mod@albedo): the albedo of a Lambertian or plastic material (colour, solid
//!   texture or image).
//! - [`conductor`](mod@conductor): η and κ of a conductor or glint material, and the measured
//!   metal presets.
//! - [`glint`](mod@glint): the microstructure of a glint material.
//! - [`normal_map`](mod@normal_map): example maps (normal or height map) and the filtered
//!   normal map.
//! - [`texture`](mod@texture): solid textures: procedural patterns, volume files and
//!   synthesized textures.
//! - [`relief`](mod@relief): the `relief` of a synthesized texture.
//! - [`store`](mod@store): the store a texture is baked into (kind, resolution, filter).

mod albedo;
mod conductor;
mod fields;
mod glint;
mod normal_map;
mod relief;
mod store;
mod texture;

use super::check::ColorKind;
use super::location::{join, Doc};
use super::raw::{RawMaterial, RawMaterialKind};
use super::{Material, MaterialKind, SceneError};
use albedo::albedo;
use conductor::eta_k;
use fields::{a_kind, reject_inapplicable};
use glam::Vec3;
use glint::glint;
use normal_map::normal_map;
use std::path::Path;
use toml::Spanned;

/// Index of refraction of the plastic coat when the file gives none (a typical polymer).
pub(super) const DEFAULT_PLASTIC_IOR: f32 = 1.5;

/// Validates one material table; `label` is its field path prefix (`material "glass"`),
/// `base` the folder relative paths start from.
pub(super) fn resolve(
    doc: &Doc,
    raw: &Spanned<RawMaterial>,
    label: &str,
    base: &Path,
) -> Result<Material, SceneError> {
    let table = raw.span();
    let raw = raw.get_ref();
    reject_inapplicable(doc, raw, label)?;
    let kind = *raw.kind.get_ref();
    let field = |key: &str| join(label, key);
    let roughness = |required: bool| -> Result<f32, SceneError> {
        let why = format!("{} material needs it, in [0, 1]", a_kind(kind));
        match (&raw.roughness, required) {
            (None, false) => Ok(0.0),
            (r, _) => doc.number(
                doc.require(r, &table, label, "roughness", &why)?,
                &field("roughness"),
                |v| (0.0..=1.0).contains(&v),
                "in [0, 1]",
            ),
        }
    };
    let ior = |default: Option<f32>| -> Result<f32, SceneError> {
        match (&raw.ior, default) {
            (None, Some(d)) => Ok(d),
            (r, _) => doc.number(
                doc.require(r, &table, label, "ior", "a dielectric needs it, in (1, 4]")?,
                &field("ior"),
                |v| v > 1.0 && v <= 4.0,
                "in (1, 4]",
            ),
        }
    };
    let mut material = Material {
        name: raw.name.get_ref().clone(),
        kind: MaterialKind::Lambertian,
        color: Vec3::ZERO,
        k: Vec3::ZERO,
        emission: Vec3::ZERO,
        roughness: 0.0,
        ior: 1.0,
        texture: None,
        glint: None,
        albedo_map: None,
        normal_map: None,
    };
    if kind != RawMaterialKind::Glint {
        material.normal_map = normal_map(doc, raw, label, base)?;
    }
    match kind {
        RawMaterialKind::Lambertian | RawMaterialKind::Plastic => {
            (material.color, material.texture, material.albedo_map) =
                albedo(doc, raw, &table, label, base)?;
            if kind == RawMaterialKind::Plastic {
                material.kind = MaterialKind::Plastic;
                material.roughness = roughness(true)?;
                material.ior = ior(Some(DEFAULT_PLASTIC_IOR))?;
            }
        }
        RawMaterialKind::Conductor => {
            material.kind = MaterialKind::Conductor;
            (material.color, material.k) = eta_k(doc, raw, &table, label)?;
            material.roughness = roughness(true)?;
        }
        RawMaterialKind::Glint => {
            material.kind = MaterialKind::Glint;
            (material.color, material.k) = eta_k(doc, raw, &table, label)?;
            material.glint = Some(glint(doc, raw, &table, label, base)?);
        }
        RawMaterialKind::Dielectric => {
            material.kind = MaterialKind::Dielectric;
            material.color = match &raw.color {
                Some(c) => doc.color(c, &field("color"), ColorKind::Albedo)?,
                None => Vec3::ONE,
            };
            material.roughness = roughness(false)?;
            material.ior = ior(None)?;
        }
        RawMaterialKind::Emissive => {
            material.kind = MaterialKind::Emissive;
            let e = doc.require(
                &raw.emission,
                &table,
                label,
                "emission",
                "an emissive material needs it",
            )?;
            material.emission = doc.color(e, &field("emission"), ColorKind::Unbounded)?;
        }
    }
    Ok(material)
}
