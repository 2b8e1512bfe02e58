//! The microstructure of a glint material: its example, blending, patches, intrinsic roughness,
//! scale and surface coordinates. Separate because no other kind has these keys or limits.

use super::normal_map::{map_example, LoadedMap};
use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawGlintBlend, RawGlintEvaluation, RawGlintUv, RawMaterial};
use crate::scene::{GlintProjection, GlintSpec, SceneError};
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

/// Narrowest intrinsic roughness σ_r of a glint material: below it a texel's element is far
/// narrower than a 16-bit range step and f32 sums lose it.
pub const MIN_GLINT_ROUGHNESS: f32 = 1e-3;
/// Widest intrinsic roughness: beyond it the P-NDF is no longer a glint.
pub const MAX_GLINT_ROUGHNESS: f32 = 0.5;

/// The microstructure of a glint material: the example (a normal map or a height map, PNG),
/// its blending and patches, σ_r, scale and surface coordinates.
pub(super) fn glint(
    doc: &Doc,
    raw: &RawMaterial,
    table: &Range<usize>,
    label: &str,
    base: &Path,
) -> Result<GlintSpec, SceneError> {
    use crate::glint::{BlendMode, ByExampleMap};
    let field = |key: &str| join(label, key);
    let Some(LoadedMap {
        example,
        source,
        fit,
        from_heights,
    }) = map_example(doc, raw, label, base)?
    else {
        return Err(doc.invalid(
            table.clone(),
            field("normal_map"),
            "missing (a glint material needs its example: normal_map or height_map, a PNG)",
        ));
    };
    let example_field = if from_heights {
        "height_map"
    } else {
        "normal_map"
    };
    let size = example.size() as u32;
    let patch = match &raw.patch {
        Some(p) => {
            let v = doc.integer(p, &field("patch"), 2..=size / 4)?;
            if !v.is_power_of_two() {
                return Err(doc.invalid(
                    p.span(),
                    field("patch"),
                    format!("{v} is not a power of two (target patch edge in texels, 2 to {} for this {size}² example)", size / 4),
                ));
            }
            v
        }
        None => size / 4,
    };
    let mode = match raw.blend.as_ref().map(|b| *b.get_ref()) {
        Some(RawGlintBlend::None) => BlendMode::None,
        Some(RawGlintBlend::Linear) => BlendMode::Linear,
        Some(RawGlintBlend::Variance) => BlendMode::Variance,
        Some(RawGlintBlend::Histogram) | None => BlendMode::Histogram,
    };
    let seed = raw.seed.as_ref().map_or(1, |s| *s.get_ref());
    let shadow_alpha = rms_slope(example.texels()).clamp(0.01, 1.0);
    let map = ByExampleMap::new(example, patch, seed, mode)
        .map_err(|e| doc.invalid(table.clone(), field(example_field), e.to_string()))?;
    let why = format!(
        "a glint material needs it: the width of its Gaussian elements in normal units, in [{MIN_GLINT_ROUGHNESS}, {MAX_GLINT_ROUGHNESS}]"
    );
    let sigma_r = doc.number(
        doc.require(
            &raw.intrinsic_roughness,
            table,
            label,
            "intrinsic_roughness",
            &why,
        )?,
        &field("intrinsic_roughness"),
        |v| (MIN_GLINT_ROUGHNESS..=MAX_GLINT_ROUGHNESS).contains(&v),
        &format!("in [{MIN_GLINT_ROUGHNESS}, {MAX_GLINT_ROUGHNESS}]"),
    )?;
    let scale = doc.number(
        doc.require(
            &raw.scale,
            table,
            label,
            "scale",
            "a glint material needs it: the example's width in scene units, > 0",
        )?,
        &field("scale"),
        |v| v > 0.0,
        "> 0",
    )?;
    let uv = doc.require(
        &raw.uv,
        table,
        label,
        "uv",
        "a glint material says where its surface coordinates come from: \"planar\" (object x, z: quads and bent quads), \"spherical\" (about the built-in sphere's centre) or \"mesh\" (the mesh's texture coordinates)",
    )?;
    Ok(GlintSpec {
        map: Arc::new(map),
        source,
        fit,
        intrinsic_roughness: sigma_r,
        scale,
        projection: match uv.get_ref() {
            RawGlintUv::Planar => GlintProjection::Planar,
            RawGlintUv::Spherical => GlintProjection::Spherical,
            RawGlintUv::Mesh => GlintProjection::Mesh,
        },
        explicit: matches!(
            raw.evaluation.as_ref().map(|e| *e.get_ref()),
            Some(RawGlintEvaluation::Explicit)
        ),
        shadow_alpha,
    })
}

/// RMS slope |n_xy| / n_z of an example's normals.
fn rms_slope(texels: &[glam::Vec2]) -> f32 {
    let sum: f64 = texels
        .iter()
        .map(|n| {
            let z2 = (1.0 - n.length_squared()).max(1e-4);
            (n.length_squared() / z2) as f64
        })
        .sum();
    (sum / texels.len().max(1) as f64).sqrt() as f32
}
