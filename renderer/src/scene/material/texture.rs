//! Solid textures: the `texture` table of a material, as a procedural pattern (marble, wood,
//! checker), a volume file or a texture synthesized from an exemplar, and the checks they share
//! (no pattern keys where there is no pattern, a store where one is required). Separate
//! because a texture is a table of its own, with its own kinds and keys.

use super::fields::must_exist;
use super::relief::{relief, NO_RELIEF_CHANNEL};
use super::store::store;
use crate::scene::check::ColorKind;
use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawTexture, RawTextureKind};
use crate::scene::volume::{mean_linear, VolumeTexture};
use crate::scene::{SceneError, SolidTexture, SolidTextureKind, StoreSpec, SynthesizedSpec};
use glam::Vec3;
use lazysolid_synth::solid::lazy::MemoryPolicy;
use lazysolid_synth::solid::{SolidRecipe, DEFAULT_SOLID_SEED};
use std::ops::Range;
use std::path::Path;
use toml::Spanned;

/// A solid texture table: a procedural pattern (`color_a`, `color_b`, `scale`) or a volume
/// file (`path`, read through a store only).
pub(super) fn texture(
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
    Ok(SolidTexture::of_volume(volume, store))
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
    let seed = match &raw.seed {
        Some(s) => *s.get_ref(),
        None => DEFAULT_SOLID_SEED,
    };
    let recipe = SolidRecipe {
        seed,
        ..SolidRecipe::new(&file)
    };
    // The recipe's exemplars, as the bake will prepare them: a bad image fails here.
    let sources = recipe
        .load()
        .map_err(|e| doc.invalid(exemplar.span(), field.clone(), e.to_string()))?;
    let image = sources.given.role(0);
    let (w, h) = (image.width, image.height);
    let mean = Vec3::from_array(mean_linear((0..w * h).map(|i| image.at(i % w, i / w))));
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
            colours: recipe,
            fit: sources.fits[0].clone(),
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
