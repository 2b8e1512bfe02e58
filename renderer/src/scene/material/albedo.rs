//! The albedo of a Lambertian or plastic material: a colour, a solid texture or an albedo map
//! (an image read at the mesh's texture coordinates), exactly one of them. Separate because
//! the two kinds share it and it is where an albedo map is read.

use super::fields::{a_kind, must_exist};
use super::texture::texture;
use crate::image_texture::ImageTexture;
use crate::scene::check::ColorKind;
use crate::scene::location::{join, Doc};
use crate::scene::raw::RawMaterial;
use crate::scene::{ImageMap, SceneError, SolidTexture};
use glam::Vec3;
use lazysolid_compute::ctree::colour::ColourTrees;
use lazysolid_compute::ctree::{CtreeError, CtreeOptions};
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

/// The albedo of a Lambertian or plastic material: a colour, a solid texture or an image read
/// at the mesh's texture coordinates, one of them. With a texture, `color` is the mean of its
/// two colours, with an image the image's mean (flat stand-ins for previews).
pub(super) fn albedo(
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
        let ctree = match &raw.albedo_ctree_step {
            None => None,
            Some(step) => {
                let key = join(label, "albedo_ctree_step");
                let trees = ctree_of(&image, *step.get_ref())
                    .map_err(|e| doc.invalid(step.span(), key, e.to_string()))?;
                Some((*step.get_ref(), Arc::new(trees)))
            }
        };
        return Ok((
            mean,
            None,
            Some(ImageMap {
                source: file,
                image: Arc::new(image),
                ctree,
            }),
        ));
    }
    if let Some(step) = &raw.albedo_ctree_step {
        let why = "compresses the albedo_map, which this material does not have";
        return Err(doc.invalid(step.span(), join(label, "albedo_ctree_step"), why));
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

/// The image's finest level as three compressed trees (YCoCg-R) at `step` grey levels.
fn ctree_of(image: &ImageTexture, step: f32) -> Result<ColourTrees, CtreeError> {
    let rgb: Vec<u8> = image.levels[0]
        .iter()
        .flat_map(|&t| [t as u8, (t >> 8) as u8, (t >> 16) as u8])
        .collect();
    let options = CtreeOptions {
        step,
        ..Default::default()
    };
    ColourTrees::build(&image.name, &rgb, image.width, image.height, &options)
}
