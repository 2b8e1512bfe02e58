//! Triangle meshes: loading (OBJ, OFF), validation, bounds and the unit-cube normalization that
//! every voxel grid of lazysolid is defined in, and the built-in shapes scenes may use.

mod error;
mod obj;
mod off;
mod shapes;

pub use error::MeshError;
pub use shapes::MAX_ICOSPHERE_SUBDIVISIONS;

use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// An indexed triangle mesh.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as indices into `positions`, counter-clockwise when seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates, one per vertex (as `positions`), when the file gives them for every
    /// face: image textures and normal maps read them (v up, as OBJ writes them: v = 0 is the
    /// image's bottom row). A vertex on a UV seam is as many vertices as it has coordinates.
    pub uvs: Option<Vec<Vec2>>,
    /// Where the mesh was read from (for messages).
    pub source: PathBuf,
}

/// Axis-aligned bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    /// Smallest coordinates.
    pub min: Vec3,
    /// Largest coordinates.
    pub max: Vec3,
}

impl Bounds {
    /// Extent along each axis.
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }
}

impl Mesh {
    /// Loads `.obj` or `.off` by extension and validates the result.
    ///
    /// # Errors
    /// A missing or unreadable file, an unknown extension, a malformed file (with its line and
    /// field), or a mesh that fails [`Mesh::validate`].
    pub fn load(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let mesh = match ext.as_deref() {
            Some("off") => off::load(path)?,
            Some("obj") => obj::load(path)?,
            _ => {
                return Err(MeshError::UnknownFormat {
                    file: path.to_path_buf(),
                })
            }
        };
        mesh.validate()?;
        Ok(mesh)
    }

    /// Loads like [`Mesh::load`] and moves the mesh into the unit cube
    /// ([`Mesh::normalize_to_unit_cube`]): how voxel grids, stores and benchmarks take meshes.
    ///
    /// # Errors
    /// As [`Mesh::load`].
    pub fn load_unit_cube(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
        let mut mesh = Mesh::load(path)?;
        mesh.normalize_to_unit_cube();
        Ok(mesh)
    }

    /// Checks what every consumer relies on: at least one triangle, finite coordinates, indices
    /// in range.
    pub fn validate(&self) -> Result<(), MeshError> {
        let file = self.source.clone();
        if self.triangles.is_empty() {
            return Err(MeshError::Empty {
                file,
                vertices: self.positions.len(),
            });
        }
        if let Some((i, p)) = self
            .positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite())
        {
            return Err(MeshError::NonFinite {
                file,
                vertex: i,
                value: format!("{p:?}"),
            });
        }
        let n = self.positions.len();
        if let Some(uvs) = &self.uvs {
            if uvs.len() != n {
                return Err(MeshError::UvCount {
                    file,
                    uvs: uvs.len(),
                    vertices: n,
                });
            }
            if let Some((i, uv)) = uvs.iter().enumerate().find(|(_, uv)| !uv.is_finite()) {
                return Err(MeshError::NonFinite {
                    file,
                    vertex: i,
                    value: format!("texture coordinate {uv:?}"),
                });
            }
        }
        for (t, tri) in self.triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange {
                    file,
                    triangle: t,
                    index,
                    vertices: n,
                });
            }
        }
        Ok(())
    }

    /// Axis-aligned bounds of the vertices.
    pub fn bounds(&self) -> Bounds {
        let min = self
            .positions
            .iter()
            .copied()
            .fold(Vec3::splat(f32::INFINITY), Vec3::min);
        let max = self
            .positions
            .iter()
            .copied()
            .fold(Vec3::splat(f32::NEG_INFINITY), Vec3::max);
        Bounds { min, max }
    }

    /// Scales and translates the mesh uniformly so that its longest axis spans [0, 1] and the
    /// other axes are centred in the unit cube: the convention of every voxel grid in lazysolid
    /// (a grid of resolution R covers [0, 1]^3 with cells of size 1/R). Returns the scale and
    /// the offset, so that `normalized = (original - min) * scale + offset`.
    pub fn normalize_to_unit_cube(&mut self) -> (f32, Vec3) {
        let b = self.bounds();
        let extent = b.size().max_element();
        let scale = if extent > 0.0 { 1.0 / extent } else { 1.0 };
        let offset = (Vec3::ONE - b.size() * scale) * 0.5;
        for p in &mut self.positions {
            *p = (*p - b.min) * scale + offset;
        }
        (scale, offset)
    }
}
