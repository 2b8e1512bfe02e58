//! A material's example map (a tangent-space normal map or a height map, not both) and the
//! filtered normal map of a Lambertian, conductor or plastic material made from it. Separate
//! because the glint microstructure reads the same example maps.

use super::fields::must_exist;
use crate::image_texture::ImageTexture;
use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawMaterial, RawNormalFilter};
use crate::scene::{NormalFilter, NormalMap, SceneError};
use std::path::Path;
use std::sync::Arc;
use toml::Spanned;

/// vMF lobes per texel when a material gives no `vmf_lobes`: the thesis finds 3–4 lobes
/// "excellent" (seed 000 §7.4).
pub const DEFAULT_VMF_LOBES: usize = 4;

/// A map file read as an example: what [`map_example`] returns.
pub(super) struct LoadedMap {
    pub(super) example: crate::glint::NormalExample,
    pub(super) source: std::path::PathBuf,
    pub(super) fit: crate::glint::example::MapFit,
    pub(super) from_heights: bool,
}

/// A material's example map: `normal_map` (tangent-space PNG) or `height_map` (its grey times
/// `height_scale`, default 1, in texel units), not both, as
/// [`NormalExample`](crate::glint::NormalExample)s with the file, how it was fitted and whether
/// it came from heights; `None` when neither is given.
pub(super) fn map_example(
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
pub(super) fn normal_map(
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
