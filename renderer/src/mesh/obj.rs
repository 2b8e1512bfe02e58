//! OBJ through tobj: every model of the file merged into one triangulated mesh.
//!
//! tobj gives each model (each group or material run) its own copy of the vertices it uses,
//! so a surface split into groups — a fragment's outer and cut faces — would come apart along
//! the group borders. So the file is read twice when it has several models: once as written,
//! which checks it and names the group in errors, and once with its grouping lines (`o`,
//! `g`, `usemtl`, `mtllib`) made comments, as one model, whose vertices are the file's own
//! `v` (and `vt`) indices. Vertices are never welded by position: two `v` lines at the same
//! point stay two vertices, as a fragment's separated sheets need (`fracture::manifold`),
//! and a corner with two texture coordinates (a UV seam) stays two vertices.

use super::{Mesh, MeshError};
use glam::{Vec2, Vec3};
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
    let has_uvs = models
        .iter()
        .any(|m| !m.mesh.indices.is_empty() && !m.mesh.texcoords.is_empty());
    if has_uvs {
        if let Some(m) = models
            .iter()
            .find(|m| !m.mesh.indices.is_empty() && m.mesh.texcoords.is_empty())
        {
            return Err(MeshError::PartialUvs {
                file: path.to_path_buf(),
                model: m.name.clone(),
            });
        }
    }
    let with_faces = models.iter().filter(|m| !m.mesh.indices.is_empty()).count();
    let models = if with_faces > 1 {
        one_model(path, &options)?
    } else {
        models
    };
    let mut positions: Vec<Vec3> = Vec::new();
    let mut uvs: Vec<Vec2> = Vec::new();
    let mut triangles = Vec::new();
    let mut earlier: HashMap<[u32; 5], u32> = HashMap::new();
    for model in models {
        let texcoords = &model.mesh.texcoords;
        let bits: Vec<[u32; 5]> = model
            .mesh
            .positions
            .chunks_exact(3)
            .enumerate()
            .map(|(i, p)| {
                let uv = match texcoords.get(2 * i..2 * i + 2) {
                    Some(t) if has_uvs => [t[0].to_bits(), t[1].to_bits()],
                    _ => [0, 0],
                };
                [p[0].to_bits(), p[1].to_bits(), p[2].to_bits(), uv[0], uv[1]]
            })
            .collect();
        let index: Vec<u32> = bits
            .iter()
            .map(|b| match earlier.get(b) {
                Some(&i) => i,
                None => {
                    positions.push(Vec3::new(
                        f32::from_bits(b[0]),
                        f32::from_bits(b[1]),
                        f32::from_bits(b[2]),
                    ));
                    uvs.push(Vec2::new(f32::from_bits(b[3]), f32::from_bits(b[4])));
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
        uvs: has_uvs.then_some(uvs),
        source: path.to_path_buf(),
    })
}

/// The file read again as one model: its grouping lines turned into comments (keeping the
/// line count), so that tobj numbers vertices by the file's own indices across groups.
fn one_model(path: &Path, options: &tobj::LoadOptions) -> Result<Vec<tobj::Model>, MeshError> {
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io {
        file: path.to_path_buf(),
        source,
    })?;
    let mut text = Vec::with_capacity(bytes.len());
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        let word = line
            .trim_ascii_start()
            .split(|b| b.is_ascii_whitespace())
            .next()
            .unwrap_or_default();
        if [&b"o"[..], b"g", b"usemtl", b"mtllib"].contains(&word) {
            text.extend_from_slice(b"#");
        }
        text.extend_from_slice(line);
    }
    let (models, _) = tobj::load_obj_buf(&mut text.as_slice(), options, |_| Ok(Default::default()))
        .map_err(|e| MeshError::Obj {
            file: path.to_path_buf(),
            problem: e.to_string(),
        })?;
    Ok(models)
}
