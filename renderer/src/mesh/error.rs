//! Mesh loading errors: each names the file and, where it applies, the line and field.

use std::path::PathBuf;

/// Why a mesh could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Neither `.obj` nor `.off`.
    #[error("{file}: unknown mesh format (expected a .obj or .off file)")]
    UnknownFormat {
        /// The file.
        file: PathBuf,
    },
    /// A syntax or content error at a line.
    #[error("{file}:{line}: {field}: {problem}")]
    Parse {
        /// The file.
        file: PathBuf,
        /// 1-based line number (0 when the problem is the end of the file).
        line: usize,
        /// What was being read, e.g. `vertex 12 coordinate y`.
        field: String,
        /// What is wrong.
        problem: String,
    },
    /// The OBJ reader failed.
    #[error("{file}: OBJ: {problem}")]
    Obj {
        /// The file.
        file: PathBuf,
        /// tobj's description.
        problem: String,
    },
    /// No triangle at all.
    #[error("{file}: the mesh has no triangles ({vertices} vertices)")]
    Empty {
        /// The file.
        file: PathBuf,
        /// Its vertex count.
        vertices: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("{file}: vertex {vertex} has a non-finite coordinate {value}")]
    NonFinite {
        /// The file.
        file: PathBuf,
        /// The vertex index.
        vertex: usize,
        /// Its coordinates.
        value: String,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("{file}: triangle {triangle} refers to vertex {index}, but the mesh has {vertices} vertices")]
    IndexOutOfRange {
        /// The file.
        file: PathBuf,
        /// The triangle.
        triangle: usize,
        /// The bad index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// Texture coordinates that do not come one per vertex.
    #[error("{file}: {uvs} texture coordinates for {vertices} vertices (one per vertex expected)")]
    UvCount {
        /// The file.
        file: PathBuf,
        /// Number of texture coordinates.
        uvs: usize,
        /// Number of vertices.
        vertices: usize,
    },
    /// Some faces have texture coordinates and others not: a material reading them would find
    /// nothing on part of the surface.
    #[error("{file}: object or group {model:?} has no texture coordinates (vt) while others have: give every face its vt, or none")]
    PartialUvs {
        /// The file.
        file: PathBuf,
        /// The first model (object or group) without them.
        model: String,
    },
}
