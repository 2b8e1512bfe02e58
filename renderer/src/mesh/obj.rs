//! OBJ through tobj: every model of the file merged into one triangulated mesh.
//!
//! tobj gives each model (each group or material run) its own copy of the vertices it uses,
//! so a surface split into groups — a fragment's outer and cut faces — would come apart along
//! the group borders. A vertex of a later model at exactly the position of a vertex of an
//! earlier one is therefore the same vertex; vertices within one model are kept as written.

use super::{Mesh, MeshError};
use glam::Vec3;
use std::collections::HashMap;
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
    let mut positions: Vec<Vec3> = Vec::new();
    let mut triangles = Vec::new();
    let mut earlier: HashMap<[u32; 3], u32> = HashMap::new();
    for model in models {
        let bits: Vec<[u32; 3]> = model
            .mesh
            .positions
            .chunks_exact(3)
            .map(|p| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits()])
            .collect();
        let index: Vec<u32> = bits
            .iter()
            .map(|b| match earlier.get(b) {
                Some(&i) => i,
                None => {
                    positions.push(Vec3::from_array(b.map(f32::from_bits)));
                    positions.len() as u32 - 1
                }
            })
            .collect();
        for (b, &i) in bits.into_iter().zip(&index) {
            earlier.entry(b).or_insert(i);
        }
        triangles.extend(
            model
                .mesh
                .indices
                .chunks_exact(3)
                .map(|t| [0, 1, 2].map(|k| index[t[k] as usize])),
        );
    }
    Ok(Mesh {
        positions,
        triangles,
        source: path.to_path_buf(),
    })
}
