//! The `relief` of a synthesized texture: the slope of its features' walls, which bends the
//! shading normal along the feature channel. Separate because it ties a texture to its store's
//! filter and has limits of its own.

use crate::scene::location::{join, Doc};
use crate::scene::raw::RawTexture;
use crate::scene::{SceneError, StoreFilter, StoreSpec};

/// Why a texture that is not synthesized has no `relief`.
pub(super) const NO_RELIEF_CHANNEL: &str = "relief is read from a synthesized texture's feature channel (kind = \"synthesized\"); a procedural pattern or a volume file has none";

/// Largest `relief`: the slope of the features' walls (height per unit of feature distance),
/// 4 being 76° walls; beyond, the bent normals of a groove's two walls face away from most
/// views.
pub const MAX_RELIEF: f32 = 4.0;

/// The `relief` of a synthesized texture read through `store` (0 when absent).
pub(super) fn relief(
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
