//! The store a solid texture is baked into: its kind, its resolution (checked against what the
//! kind supports) and its filter. Separate because it is the one place the scene names the
//! sparse stores of `lazysolid_compute`.

use crate::scene::location::{join, Doc};
use crate::scene::raw::{RawStoreFilter, RawTexture};
use crate::scene::{SceneError, StoreFilter, StoreKind, StoreSpec};

/// Largest resolution a solid texture may be baked at (the voxel grids' limit).
pub const MAX_STORE_RESOLUTION: u32 = 2048;

/// The optional `store`, `resolution` and `filter` of a texture: all or none of `store` and
/// `resolution`; `filter` only with a store (default nearest).
pub(super) fn store(
    doc: &Doc,
    raw: &RawTexture,
    label: &str,
) -> Result<Option<StoreSpec>, SceneError> {
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
            let kind_ = StoreKind::from_name(kind.get_ref()).ok_or_else(|| {
                doc.invalid(
                    kind.span(),
                    join(label, "store"),
                    format!(
                        "unknown store `{}`, expected one of {}",
                        kind.get_ref(),
                        StoreKind::names()
                    ),
                )
            })?;
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
            format!("is required with `resolution` ({})", StoreKind::names()),
        )),
    }
}
