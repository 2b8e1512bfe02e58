//! OBJ through tobj: every model of the file merged into one triangulated mesh.

use super::{Mesh, MeshError};
use glam::Vec3;
use std::path::Path;

pub(super) fn load(path: &Path) -> Result<Mesh, MeshError> {
    if let Err(source) = std::fs::metadata(path) {
        return Err(MeshError::Io {
            file: path.to_path_buf(),
            source,
        });
    }
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| MeshError::Obj {
        file: path.to_path_buf(),
        problem: e.to_string(),
    })?;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for model in models {
        let base = positions.len() as u32;
        positions.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        triangles.extend(
            model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
    }
    Ok(Mesh {
        positions,
        triangles,
        source: path.to_path_buf(),
    })
}
