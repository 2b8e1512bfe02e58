//! `[[material]]` tables: which keys each kind needs and accepts, the measured metal presets,
//! and solid textures.

use super::check::ColorKind;
use super::location::{join, Doc};
use super::raw::{
    RawGlintBlend, RawGlintEvaluation, RawGlintUv, RawMaterial, RawMaterialKind, RawNormalFilter,
    RawPreset, RawStoreFilter, RawStoreKind, RawTexture, RawTextureKind,
};
use super::volume::{mean_linear, VolumeTexture};
use super::{
    GlintProjection, GlintSpec, ImageMap, Material, MaterialKind, NormalFilter, NormalMap,
    SceneError, SolidTexture, SolidTextureKind, StoreFilter, StoreKind, StoreSpec, SynthesizedSpec,
};
use crate::image_texture::ImageTexture;
use glam::Vec3;
use lazysolid_synth::solid::lazy::MemoryPolicy;
use lazysolid_synth::{load_solid, FitMode};
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;
use toml::Spanned;

/// vMF lobes per texel when a material gives no `vmf_lobes`: the thesis finds 3–4 lobes
/// "excellent" (seed 000 §7.4).
pub const DEFAULT_VMF_LOBES: usize = 4;

/// Index of refraction of the plastic coat when the file gives none (a typical polymer).
pub(super) const DEFAULT_PLASTIC_IOR: f32 = 1.5;

/// Complex index of refraction (η, κ) at the red, green and blue wavelengths of the common
/// sRGB reductions of measured spectral data, so that scenes get real metals by name.
pub(super) fn preset_eta_k(preset: RawPreset) -> (Vec3, Vec3) {
    match preset {
        RawPreset::Gold => (
            Vec3::new(0.143_119, 0.374_957, 1.442_48),
            Vec3::new(3.983_16, 2.385_72, 1.603_22),
        ),
        RawPreset::Silver => (
            Vec3::new(0.155_265, 0.116_723, 0.138_342),
            Vec3::new(4.828_35, 3.122_25, 2.146_96),
        ),
        RawPreset::Copper => (
            Vec3::new(0.200_438, 0.924_033, 1.102_21),
            Vec3::new(3.912_95, 2.452_85, 2.142_19),
        ),
        RawPreset::Aluminium => (
            Vec3::new(1.657_46, 0.880_369, 0.521_229),
            Vec3::new(9.223_87, 6.269_52, 4.837),
        ),
    }
}

/// "a lambertian", "an emissive", … for messages.
fn a_kind(kind: RawMaterialKind) -> String {
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
const ACCEPTED_BY: [(&str, &[RawMaterialKind]); 20] = {
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
fn reject_inapplicable(doc: &Doc, raw: &RawMaterial, label: &str) -> Result<(), SceneError> {
    let kind = *raw.kind.get_ref();
    let spans: [(&str, Option<Range<usize>>); 20] = [
        ("color", raw.color.as_ref().map(Spanned::span)),
        ("k", raw.k.as_ref().map(Spanned::span)),
        ("emission", raw.emission.as_ref().map(Spanned::span)),
        ("roughness", raw.roughness.as_ref().map(Spanned::span)),
        ("ior", raw.ior.as_ref().map(Spanned::span)),
        ("preset", raw.preset.as_ref().map(Spanned::span)),
        ("texture", raw.texture.as_ref().map(Spanned::span)),
        ("albedo_map", raw.albedo_map.as_ref().map(Spanned::span)),
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

/// A map file read as an example: what [`map_example`] returns.
struct LoadedMap {
    example: crate::glint::NormalExample,
    source: std::path::PathBuf,
    fit: crate::glint::example::MapFit,
    from_heights: bool,
}

/// A material's example map: `normal_map` (tangent-space PNG) or `height_map` (its grey times
/// `height_scale`, default 1, in texel units), not both, as [`NormalExample`]s with the file,
/// how it was fitted and whether it came from heights; `None` when neither is given.
fn map_example(
    doc: &Doc,
    raw: &RawMaterial,
    label: &str,
    base: &Path,
) -> Result<Option<LoadedMap>, SceneError> {
    use crate::glint::example::{load_height_map, load_normal_map};
    let field = |key: &str| join(label, key);
    match (&raw.normal_map, &raw.height_map) {
        (Some(_), Some(h)) => Err(doc.invalid(
            h.span(),
            field("height_map"),
            "normal_map and height_map are exclusive: give one",
        )),
        (None, None) => {
            let why = "applies only to a height_map";
            doc.reject(&raw.height_scale, label, "height_scale", why)?;
            Ok(None)
        }
        (Some(n), None) => {
            let why = "applies only to a height_map";
            doc.reject(&raw.height_scale, label, "height_scale", why)?;
            let file = base.join(n.get_ref());
            must_exist(doc, n.span().start, field("normal_map"), &file)?;
            let (example, fit) = load_normal_map(&file)
                .map_err(|e| doc.invalid(n.span(), field("normal_map"), e))?;
            Ok(Some(LoadedMap {
                example,
                source: file,
                fit,
                from_heights: false,
            }))
        }
        (None, Some(h)) => {
            let scale = match &raw.height_scale {
                Some(v) => doc.number(v, &field("height_scale"), |v| v > 0.0, "> 0")?,
                None => 1.0,
            };
            let file = base.join(h.get_ref());
            must_exist(doc, h.span().start, field("height_map"), &file)?;
            let (example, fit) = load_height_map(&file, scale)
                .map_err(|e| doc.invalid(h.span(), field("height_map"), e))?;
            Ok(Some(LoadedMap {
                example,
                source: file,
                fit,
                from_heights: true,
            }))
        }
    }
}

/// The optional normal map of a Lambertian, conductor or plastic material: a tangent-space
/// normal map or a height map (`height_scale` texel units of height per unit of grey), not
/// both; any size, fitted to the square power-of-two grid the vMF pyramid needs.
fn normal_map(
    doc: &Doc,
    raw: &RawMaterial,
    label: &str,
    base: &Path,
) -> Result<Option<NormalMap>, SceneError> {
    let field = |key: &str| join(label, key);
    let Some(LoadedMap {
        example,
        source,
        fit,
        from_heights,
    }) = map_example(doc, raw, label, base)?
    else {
        let why = "applies only with a normal_map or height_map";
        doc.reject(&raw.normal_filter, label, "normal_filter", why)?;
        doc.reject(&raw.vmf_lobes, label, "vmf_lobes", why)?;
        return Ok(None);
    };
    let example = if from_heights {
        // Image rows run down, v runs up: the slope along v is minus the slope along rows.
        let flipped = example
            .texels()
            .iter()
            .map(|n| glam::Vec2::new(n.x, -n.y))
            .collect();
        let name = source.display().to_string();
        let span = raw.height_map.as_ref().map_or(0..0, Spanned::span);
        crate::glint::NormalExample::from_normals(&name, example.size(), flipped)
            .map_err(|e| doc.invalid(span, field("height_map"), e.to_string()))?
    } else {
        example
    };
    let filter = match raw.normal_filter.as_ref().map(|f| *f.get_ref()) {
        Some(RawNormalFilter::None) => NormalFilter::None,
        Some(RawNormalFilter::Mip) => NormalFilter::Mip,
        Some(RawNormalFilter::Vmf) | None => NormalFilter::Vmf,
    };
    let range = crate::normal_map::pyramid::LOBES_PER_TEXEL;
    let lobes = match &raw.vmf_lobes {
        Some(j) => {
            if filter != NormalFilter::Vmf {
                return Err(doc.invalid(
                    j.span(),
                    field("vmf_lobes"),
                    "applies only to normal_filter = \"vmf\"",
                ));
            }
            doc.integer(
                j,
                &field("vmf_lobes"),
                *range.start() as u32..=*range.end() as u32,
            )? as usize
        }
        None => DEFAULT_VMF_LOBES,
    };
    let image = ImageTexture::from_normals(&source.display().to_string(), &example);
    Ok(Some(NormalMap {
        source,
        fit,
        example: Arc::new(example),
        image: Arc::new(image),
        filter,
        lobes,
    }))
}

/// The albedo of a Lambertian or plastic material: a colour, a solid texture or an image read
/// at the mesh's texture coordinates, one of them. With a texture, `color` is the mean of its
/// two colours, with an image the image's mean (flat stand-ins for previews).
fn albedo(
    doc: &Doc,
    raw: &RawMaterial,
    table: &Range<usize>,
    label: &str,
    base: &Path,
) -> Result<(Vec3, Option<SolidTexture>, Option<ImageMap>), SceneError> {
    if let Some(a) = &raw.albedo_map {
        let why = "albedo_map replaces color and texture as albedo: give one of them";
        doc.reject(&raw.color, label, "color", why)?;
        if raw.texture.is_some() {
            return Err(doc.invalid(a.span(), join(label, "albedo_map"), why));
        }
        let file = base.join(a.get_ref());
        must_exist(doc, a.span().start, join(label, "albedo_map"), &file)?;
        let image = ImageTexture::load_color(&file)
            .map_err(|e| doc.invalid(a.span(), join(label, "albedo_map"), e.to_string()))?;
        let top = image.levels.last().expect("a pyramid has levels")[0];
        let mean = crate::image_texture::sample::fetch_linear(&image, top).truncate();
        return Ok((
            mean,
            None,
            Some(ImageMap {
                source: file,
                image: Arc::new(image),
            }),
        ));
    }
    let (color, texture) = solid_albedo(doc, raw, table, label, base)?;
    Ok((color, texture, None))
}

/// A colour or a solid texture, not both.
fn solid_albedo(
    doc: &Doc,
    raw: &RawMaterial,
    table: &Range<usize>,
    label: &str,
    base: &Path,
) -> Result<(Vec3, Option<SolidTexture>), SceneError> {
    match (&raw.color, &raw.texture) {
        (Some(_), Some(t)) => Err(doc.invalid(
            t.span(),
            join(label, "texture"),
            "color and texture are exclusive: the texture replaces color as albedo",
        )),
        (Some(c), None) => Ok((
            doc.color(c, &join(label, "color"), ColorKind::Albedo)?,
            None,
        )),
        (None, Some(t)) => {
            let texture = texture(doc, t, &join(label, "texture"), base)?;
            Ok(((texture.color_a + texture.color_b) * 0.5, Some(texture)))
        }
        (None, None) => Err(doc.invalid(
            table.clone(),
            join(label, "color"),
            format!(
                "missing ({} material needs color, texture or albedo_map)",
                a_kind(*raw.kind.get_ref())
            ),
        )),
    }
}

/// η and κ of a conductor: a preset or both colours, not a mix.
fn eta_k(
    doc: &Doc,
    raw: &RawMaterial,
    table: &Range<usize>,
    label: &str,
) -> Result<(Vec3, Vec3), SceneError> {
    if let Some(preset) = &raw.preset {
        let why = "a preset gives both η and κ; give either preset or color and k";
        doc.reject(&raw.color, label, "color", why)?;
        doc.reject(&raw.k, label, "k", why)?;
        return Ok(preset_eta_k(*preset.get_ref()));
    }
    let why = "a conductor needs preset, or color (η) and k (κ)";
    let eta = doc.require(&raw.color, table, label, "color", why)?;
    let k = doc.require(&raw.k, table, label, "k", why)?;
    Ok((
        doc.color(eta, &join(label, "color"), ColorKind::Unbounded)?,
        doc.color(k, &join(label, "k"), ColorKind::Unbounded)?,
    ))
}

/// Narrowest intrinsic roughness σ_r of a glint material: below it a texel's element is far
/// narrower than a 16-bit range step and f32 sums lose it.
pub const MIN_GLINT_ROUGHNESS: f32 = 1e-3;
/// Widest intrinsic roughness: beyond it the P-NDF is no longer a glint.
pub const MAX_GLINT_ROUGHNESS: f32 = 0.5;

/// The microstructure of a glint material: the example (a normal map or a height map, PNG),
/// its blending and patches, σ_r, scale and surface coordinates.
fn glint(
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

/// A solid texture table: a procedural pattern (`color_a`, `color_b`, `scale`) or a volume
/// file (`path`, read through a store only).
fn texture(
    doc: &Doc,
    spanned: &Spanned<RawTexture>,
    label: &str,
    base: &Path,
) -> Result<SolidTexture, SceneError> {
    let raw = spanned.get_ref();
    let table = spanned.span();
    let store = store(doc, raw, label)?;
    let kind = match raw.kind.get_ref() {
        RawTextureKind::Marble => SolidTextureKind::Marble,
        RawTextureKind::Wood => SolidTextureKind::Wood,
        RawTextureKind::Checker => SolidTextureKind::Checker,
        RawTextureKind::Volume => return volume_texture(doc, raw, &table, label, base, store),
        RawTextureKind::Synthesized => {
            return synthesized_texture(doc, raw, &table, label, base, store)
        }
    };
    let why = "only kind = \"synthesized\" has it";
    doc.reject(&raw.exemplar, label, "exemplar", why)?;
    doc.reject(&raw.seed, label, "seed", why)?;
    doc.reject(&raw.memory, label, "memory", why)?;
    doc.reject(&raw.relief, label, "relief", NO_RELIEF_CHANNEL)?;
    doc.reject(
        &raw.path,
        label,
        "path",
        "only kind = \"volume\" reads a file",
    )?;
    let why = "a marble, wood or checker texture blends two colours";
    let color_a = doc.require(&raw.color_a, &table, label, "color_a", why)?;
    let color_b = doc.require(&raw.color_b, &table, label, "color_b", why)?;
    Ok(SolidTexture {
        kind,
        color_a: doc.color(color_a, &join(label, "color_a"), ColorKind::Albedo)?,
        color_b: doc.color(color_b, &join(label, "color_b"), ColorKind::Albedo)?,
        scale: match &raw.scale {
            Some(s) => doc.number(s, &join(label, "scale"), |v| v > 0.0, "> 0")?,
            None => 1.0,
        },
        volume: None,
        synthesized: None,
        store,
    })
}

/// Why a texture that is not synthesized has no `relief`.
const NO_RELIEF_CHANNEL: &str = "relief is read from a synthesized texture's feature channel (kind = \"synthesized\"); a procedural pattern or a volume file has none";

/// Largest `relief`: the slope of the features' walls (height per unit of feature distance),
/// 4 being 76° walls; beyond, the bent normals of a groove's two walls face away from most
/// views.
pub const MAX_RELIEF: f32 = 4.0;

/// The `relief` of a synthesized texture read through `store` (0 when absent).
fn relief(
    doc: &Doc,
    raw: &RawTexture,
    label: &str,
    store: Option<StoreSpec>,
) -> Result<f32, SceneError> {
    let Some(value) = &raw.relief else {
        return Ok(0.0);
    };
    let field = join(label, "relief");
    let v = doc.number(
        value,
        &field,
        |v| (0.0..=MAX_RELIEF).contains(&v),
        &format!("in [0, {MAX_RELIEF}]: the slope of the features' walls, height per unit of feature distance"),
    )?;
    if v > 0.0 && store.is_some_and(|s| s.filter == StoreFilter::Nearest) {
        return Err(doc.invalid(
            value.span(),
            field,
            "needs a filtered store (filter = \"trilinear\"): the bump is the filter's derivative, and a nearest lookup is flat within each voxel",
        ));
    }
    Ok(v)
}

/// A `kind = "volume"` texture table: its file, read through the store `store` only.
fn volume_texture(
    doc: &Doc,
    raw: &RawTexture,
    table: &Range<usize>,
    label: &str,
    base: &Path,
    store: Option<StoreSpec>,
) -> Result<SolidTexture, SceneError> {
    reject_pattern(
        doc,
        raw,
        label,
        "a volume texture has its colours in its file and spans the unit cube",
    )?;
    doc.reject(
        &raw.memory,
        label,
        "memory",
        "only kind = \"synthesized\" keeps a synthesis state",
    )?;
    doc.reject(&raw.relief, label, "relief", NO_RELIEF_CHANNEL)?;
    let path = doc.require(
        &raw.path,
        table,
        label,
        "path",
        "a volume texture names its NRRD file",
    )?;
    require_store(doc, raw, label, store, "a volume texture")?;
    let file = base.join(path.get_ref());
    must_exist(doc, path.span().start, join(label, "path"), &file)?;
    let volume = VolumeTexture::load(&file)
        .map_err(|problem| doc.invalid(path.span(), join(label, "path"), problem))?;
    let mean = Vec3::from_array(volume.mean_linear());
    Ok(SolidTexture {
        kind: SolidTextureKind::Volume,
        color_a: mean,
        color_b: mean,
        scale: 1.0,
        volume: Some(Arc::new(volume)),
        synthesized: None,
        store,
    })
}

/// A `kind = "synthesized"` texture table: an exemplar (asset name, or path relative to the
/// scene) synthesized lazily into the store `store`.
fn synthesized_texture(
    doc: &Doc,
    raw: &RawTexture,
    table: &Range<usize>,
    label: &str,
    base: &Path,
    store: Option<StoreSpec>,
) -> Result<SolidTexture, SceneError> {
    reject_pattern(
        doc,
        raw,
        label,
        "a synthesized texture takes its colours from its exemplar",
    )?;
    doc.reject(
        &raw.path,
        label,
        "path",
        "a synthesized texture names its `exemplar`",
    )?;
    let relief = relief(doc, raw, label, store)?;
    let exemplar = doc.require(
        &raw.exemplar,
        table,
        label,
        "exemplar",
        "a synthesized texture names its exemplar (an asset name such as \"terra\", or a path)",
    )?;
    require_store(doc, raw, label, store, "a synthesized texture")?;
    let field = join(label, "exemplar");
    let file = crate::assets::exemplar(exemplar.get_ref(), base)
        .map_err(|problem| doc.invalid(exemplar.span(), field.clone(), problem))?;
    must_exist(doc, exemplar.span().start, field.clone(), &file)?;
    // The rule `lazysolid solid` applies by default; the store's synthesis fits the same way.
    let fitted = load_solid(&file, FitMode::Auto, None)
        .map_err(|e| doc.invalid(exemplar.span(), field.clone(), e.to_string()))?;
    let image = &fitted.exemplar;
    let (w, h) = (image.width, image.height);
    let mean = Vec3::from_array(mean_linear((0..w * h).map(|i| image.at(i % w, i / w))));
    let seed = match &raw.seed {
        Some(s) => *s.get_ref(),
        None => 1,
    };
    let policy = match &raw.memory {
        Some(m) => m
            .get_ref()
            .parse::<MemoryPolicy>()
            .map_err(|e| doc.invalid(m.span(), join(label, "memory"), e.to_string()))?,
        None => MemoryPolicy::default(),
    };
    Ok(SolidTexture {
        kind: SolidTextureKind::Synthesized,
        color_a: mean,
        color_b: mean,
        scale: 1.0,
        volume: None,
        synthesized: Some(SynthesizedSpec {
            exemplar: file,
            fit: fitted.fit,
            seed,
            policy,
            relief,
        }),
        store,
    })
}

/// The errors of a procedural pattern's fields (`color_a`, `color_b`, `scale`) on a texture
/// that has none, saying `why`.
fn reject_pattern(doc: &Doc, raw: &RawTexture, label: &str, why: &str) -> Result<(), SceneError> {
    doc.reject(&raw.color_a, label, "color_a", why)?;
    doc.reject(&raw.color_b, label, "color_b", why)?;
    doc.reject(&raw.scale, label, "scale", why)
}

/// The error of a texture (`what`) read through a store only that names none.
fn require_store(
    doc: &Doc,
    raw: &RawTexture,
    label: &str,
    store: Option<StoreSpec>,
    what: &str,
) -> Result<(), SceneError> {
    match store {
        Some(_) => Ok(()),
        None => Err(doc.invalid(
            raw.kind.span(),
            join(label, "store"),
            format!("missing: {what} is read through a store (give `store` and `resolution`)"),
        )),
    }
}

/// The error of a file a scene names at byte `at` (field `field`) that does not exist.
fn must_exist(doc: &Doc, at: usize, field: String, file: &Path) -> Result<(), SceneError> {
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

/// Largest resolution a solid texture may be baked at (the voxel grids' limit).
pub const MAX_STORE_RESOLUTION: u32 = 2048;

/// The optional `store`, `resolution` and `filter` of a texture: all or none of `store` and
/// `resolution`; `filter` only with a store (default nearest).
fn store(doc: &Doc, raw: &RawTexture, label: &str) -> Result<Option<StoreSpec>, SceneError> {
    match (&raw.store, &raw.resolution) {
        (None, None) => {
            if let Some(f) = &raw.filter {
                return Err(doc.invalid(
                    f.span(),
                    join(label, "filter"),
                    "applies only to a texture baked into a store (give `store` and `resolution`)",
                ));
            }
            Ok(None)
        }
        (Some(kind), Some(res)) => {
            let kind_ = match kind.get_ref() {
                RawStoreKind::CoherentHash => StoreKind::CoherentHash,
                RawStoreKind::Octree => StoreKind::Octree,
                RawStoreKind::PerfectHash => StoreKind::PerfectHash,
                RawStoreKind::TileTree => StoreKind::TileTree,
            };
            let field = join(label, "resolution");
            let r = doc.integer(res, &field, 2..=MAX_STORE_RESOLUTION)?;
            // The N³ tree needs R as a product of per-level sizes it supports; the TileTree's
            // tile sides are R / 2^depth.
            let problem = match kind_ {
                StoreKind::Octree => lazysolid_compute::store::OctreeConfig::for_resolution(r)
                    .err()
                    .map(|e| ("an octree", e)),
                StoreKind::TileTree => lazysolid_compute::store::TileTreeConfig::default()
                    .check(r)
                    .err()
                    .map(|e| ("a tiletree", e)),
                StoreKind::CoherentHash | StoreKind::PerfectHash => None,
            };
            if let Some((what, e)) = problem {
                return Err(doc.invalid(
                    res.span(),
                    field,
                    format!("{r} cannot be {what} resolution: {e}"),
                ));
            }
            Ok(Some(StoreSpec {
                kind: kind_,
                resolution: r,
                filter: match raw.filter.as_ref().map(|f| *f.get_ref()) {
                    None | Some(RawStoreFilter::Nearest) => StoreFilter::Nearest,
                    Some(RawStoreFilter::Trilinear) => StoreFilter::Trilinear,
                },
            }))
        }
        (Some(kind), None) => Err(doc.invalid(
            kind.span(),
            join(label, "resolution"),
            "is required with `store`",
        )),
        (None, Some(res)) => Err(doc.invalid(
            res.span(),
            join(label, "store"),
            "is required with `resolution` (coherent_hash, octree, perfect_hash or tiletree)",
        )),
    }
}
