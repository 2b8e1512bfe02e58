//! The checks every material kind shares: which optional keys each kind accepts (and the
//! "does not apply" error for the others), the kind names messages use, and the error of a
//! file a scene names that does not exist. Separate because the kinds, their maps and their
//! textures all call them.

use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawMaterial, RawMaterialKind};
use crate::scene::SceneError;
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// "a lambertian", "an emissive", … for messages.
pub(super) fn a_kind(kind: RawMaterialKind) -> String {
    let name = kind_name(kind);
    let article = if name.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    format!("{article} {name}")
}

fn kind_name(kind: RawMaterialKind) -> &'static str {
    match kind {
        RawMaterialKind::Lambertian => "lambertian",
        RawMaterialKind::Conductor => "conductor",
        RawMaterialKind::Plastic => "plastic",
        RawMaterialKind::Dielectric => "dielectric",
        RawMaterialKind::Emissive => "emissive",
        RawMaterialKind::Glint => "glint",
    }
}

/// The kinds that accept each optional key, for "does not apply" messages.
const ACCEPTED_BY: [(&str, &[RawMaterialKind]); 21] = {
    use RawMaterialKind::*;
    [
        (
            "color",
            &[Lambertian, Conductor, Plastic, Dielectric, Glint],
        ),
        ("k", &[Conductor, Glint]),
        ("emission", &[Emissive]),
        ("roughness", &[Conductor, Plastic, Dielectric]),
        ("ior", &[Plastic, Dielectric]),
        ("preset", &[Conductor, Glint]),
        ("texture", &[Lambertian, Plastic]),
        ("albedo_map", &[Lambertian, Plastic]),
        ("albedo_ctree_step", &[Lambertian, Plastic]),
        ("normal_map", &[Lambertian, Conductor, Plastic, Glint]),
        ("height_map", &[Lambertian, Conductor, Plastic, Glint]),
        ("height_scale", &[Lambertian, Conductor, Plastic, Glint]),
        ("normal_filter", &[Lambertian, Conductor, Plastic]),
        ("vmf_lobes", &[Lambertian, Conductor, Plastic]),
        ("intrinsic_roughness", &[Glint]),
        ("scale", &[Glint]),
        ("blend", &[Glint]),
        ("patch", &[Glint]),
        ("seed", &[Glint]),
        ("uv", &[Glint]),
        ("evaluation", &[Glint]),
    ]
};

/// Fails on the first key present in `raw` that its kind does not accept.
pub(super) fn reject_inapplicable(
    doc: &Doc,
    raw: &RawMaterial,
    label: &str,
) -> Result<(), SceneError> {
    let kind = *raw.kind.get_ref();
    let spans: [(&str, Option<Range<usize>>); 21] = [
        ("color", raw.color.as_ref().map(Spanned::span)),
        ("k", raw.k.as_ref().map(Spanned::span)),
        ("emission", raw.emission.as_ref().map(Spanned::span)),
        ("roughness", raw.roughness.as_ref().map(Spanned::span)),
        ("ior", raw.ior.as_ref().map(Spanned::span)),
        ("preset", raw.preset.as_ref().map(Spanned::span)),
        ("texture", raw.texture.as_ref().map(Spanned::span)),
        ("albedo_map", raw.albedo_map.as_ref().map(Spanned::span)),
        (
            "albedo_ctree_step",
            raw.albedo_ctree_step.as_ref().map(Spanned::span),
        ),
        ("normal_map", raw.normal_map.as_ref().map(Spanned::span)),
        ("height_map", raw.height_map.as_ref().map(Spanned::span)),
        ("height_scale", raw.height_scale.as_ref().map(Spanned::span)),
        (
            "normal_filter",
            raw.normal_filter.as_ref().map(Spanned::span),
        ),
        ("vmf_lobes", raw.vmf_lobes.as_ref().map(Spanned::span)),
        (
            "intrinsic_roughness",
            raw.intrinsic_roughness.as_ref().map(Spanned::span),
        ),
        ("scale", raw.scale.as_ref().map(Spanned::span)),
        ("blend", raw.blend.as_ref().map(Spanned::span)),
        ("patch", raw.patch.as_ref().map(Spanned::span)),
        ("seed", raw.seed.as_ref().map(Spanned::span)),
        ("uv", raw.uv.as_ref().map(Spanned::span)),
        ("evaluation", raw.evaluation.as_ref().map(Spanned::span)),
    ];
    for ((key, span), (_, kinds)) in spans.into_iter().zip(ACCEPTED_BY) {
        if let Some(span) = span {
            if !kinds.contains(&kind) {
                let accepted: Vec<&str> = kinds.iter().map(|&k| kind_name(k)).collect();
                return Err(doc.invalid(
                    span,
                    join(label, key),
                    format!(
                        "does not apply to {} material (accepted by: {})",
                        a_kind(kind),
                        accepted.join(", ")
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The error of a file a scene names at byte `at` (field `field`) that does not exist.
pub(super) fn must_exist(
    doc: &Doc,
    at: usize,
    field: String,
    file: &Path,
) -> Result<(), SceneError> {
    if file.exists() {
        return Ok(());
    }
    Err(SceneError::MissingFile {
        file: doc.file.to_path_buf(),
        line: doc.line(at),
        field,
        missing: file.to_path_buf(),
    })
}
