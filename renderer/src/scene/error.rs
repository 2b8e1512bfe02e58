//! Scene loading errors. Every one that comes from the file's content names the scene file,
//! the 1-based line and the field path (`material "glass".ior`, `camera.fov_y`,
//! `instance #2.scale`), so that a user can go straight to the mistake.

use crate::mesh::MeshError;
use std::path::PathBuf;

/// Why a scene could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The scene file itself could not be read.
    #[error("{}: cannot read the scene: {source}", file.display())]
    Io {
        /// The scene file.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The text is not valid TOML.
    #[error("{}:{line}: TOML syntax error: {problem}", file.display())]
    Syntax {
        /// The scene file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// The TOML parser's description.
        problem: String,
    },
    /// Valid TOML that is not a valid scene: unknown key, wrong type, missing or out-of-range
    /// value, unknown or duplicate name, inconsistent combination.
    #[error("{}:{line}: {field}: {problem}", file.display())]
    Invalid {
        /// The scene file.
        file: PathBuf,
        /// 1-based line.
        line: usize,
        /// Path of the offending field, e.g. `material "glass".ior`.
        field: String,
        /// What is wrong and what would be accepted.
        problem: String,
    },
    /// A file the scene refers to (mesh or environment map) does not exist.
    #[error("{}:{line}: {field}: {} does not exist", file.display(), missing.display())]
    MissingFile {
        /// The scene file.
        file: PathBuf,
        /// 1-based line of the reference.
        line: usize,
        /// Path of the field holding the reference.
        field: String,
        /// The referenced file, resolved against the scene's folder.
        missing: PathBuf,
    },
    /// A referenced mesh exists but could not be loaded.
    #[error("{}:{line}: {field}: {source}", file.display())]
    Mesh {
        /// The scene file.
        file: PathBuf,
        /// 1-based line of the reference.
        line: usize,
        /// Path of the field holding the reference.
        field: String,
        /// The mesh loader's error, which names the mesh file and its own line (boxed: it is
        /// the largest variant and every `Result` of the loader carries it).
        source: Box<MeshError>,
    },
}
