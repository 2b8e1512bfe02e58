//! `[[mesh]]` tables: a mesh file (normalized into the unit cube unless told otherwise) or a
//! built-in shape.

use super::location::{join, Doc};
use super::raw::{RawMesh, RawShape};
use super::{SceneError, SceneMesh};
use crate::mesh::{Mesh, MAX_ICOSPHERE_SUBDIVISIONS};
use std::path::Path;
use toml::Spanned;

/// Subdivisions of `shape = "sphere"` when the file gives none: 1280 triangles, smooth enough
/// at the resolutions of tests and previews.
pub const DEFAULT_SPHERE_SUBDIVISIONS: u32 = 3;

/// Validates one mesh table and loads or generates its triangles; `label` is its field path
/// prefix (`mesh "bunny"`), `base` the folder relative paths start from.
pub(super) fn mesh(
    doc: &Doc,
    raw: &Spanned<RawMesh>,
    label: &str,
    base: &Path,
) -> Result<SceneMesh, SceneError> {
    let table = raw.span();
    let raw = raw.get_ref();
    let field = |key: &str| join(label, key);
    let mesh = match (&raw.path, &raw.shape) {
        (Some(_), Some(s)) => {
            return Err(doc.invalid(
                s.span(),
                field("shape"),
                "path and shape are exclusive: a mesh is a file or a built-in shape",
            ))
        }
        (None, None) => {
            return Err(doc.invalid(
                table,
                label,
                "needs path = \"file.obj|off\" or shape = \"quad\" | \"cube\" | \"sphere\"",
            ))
        }
        (Some(p), None) => {
            doc.reject(
                &raw.subdivisions,
                label,
                "subdivisions",
                "only shape = \"sphere\" has it",
            )?;
            let line = doc.line(p.span().start);
            let path = base.join(p.get_ref());
            if !path.exists() {
                return Err(SceneError::MissingFile {
                    file: doc.file.to_path_buf(),
                    line,
                    field: field("path"),
                    missing: path,
                });
            }
            let mut mesh = Mesh::load(&path).map_err(|source| SceneError::Mesh {
                file: doc.file.to_path_buf(),
                line,
                field: field("path"),
                source: Box::new(source),
            })?;
            if raw.normalize.as_ref().is_none_or(|n| *n.get_ref()) {
                mesh.normalize_to_unit_cube();
            }
            mesh
        }
        (None, Some(s)) => {
            doc.reject(
                &raw.normalize,
                label,
                "normalize",
                "only mesh files have it: shapes are generated in the unit cube",
            )?;
            match s.get_ref() {
                RawShape::Quad | RawShape::Cube => doc.reject(
                    &raw.subdivisions,
                    label,
                    "subdivisions",
                    "only shape = \"sphere\" has it",
                )?,
                RawShape::Sphere => {}
            }
            match s.get_ref() {
                RawShape::Quad => Mesh::unit_quad(),
                RawShape::Cube => Mesh::unit_cube(),
                RawShape::Sphere => Mesh::icosphere(match &raw.subdivisions {
                    Some(n) => {
                        doc.integer(n, &field("subdivisions"), 0..=MAX_ICOSPHERE_SUBDIVISIONS)?
                    }
                    None => DEFAULT_SPHERE_SUBDIVISIONS,
                }),
            }
        }
    };
    Ok(SceneMesh {
        name: raw.name.get_ref().clone(),
        mesh,
        cut_from: None,
    })
}
