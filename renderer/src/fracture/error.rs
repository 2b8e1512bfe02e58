//! Errors of the fracture code.

use std::path::PathBuf;

/// Why a split or fracture could not be made. Every variant that concerns a mesh names it by
/// its `source` path, because fracture usually runs on scenes with several meshes.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FractureError {
    /// The mesh has no triangles.
    #[error("{}: mesh has no triangles", mesh.display())]
    Empty {
        /// The mesh's source path.
        mesh: PathBuf,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("{}: triangle {triangle} refers to vertex {index}, but there are {vertex_count} vertices", mesh.display())]
    IndexOutOfRange {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Index of the triangle.
        triangle: usize,
        /// The bad vertex index.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A triangle uses the same vertex twice; such a triangle has no well-defined edges.
    #[error("{}: triangle {triangle} uses a vertex twice", mesh.display())]
    RepeatedIndex {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Index of the triangle.
        triangle: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("{}: vertex {vertex} is not finite", mesh.display())]
    NonFinite {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Index of the vertex.
        vertex: usize,
    },
    /// The mesh is not closed (some edge is used more often in one direction than the other),
    /// so it does not bound a solid that can be cut.
    #[error(
        "{}: mesh is not closed: {boundary_edges} boundary edge(s) (used by one triangle), \
         {non_manifold_edges} non-manifold edge(s) (used by several triangles, more often in one direction than the other)",
        mesh.display()
    )]
    NotClosed {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Undirected edges used by exactly one triangle.
        boundary_edges: usize,
        /// Undirected edges used by several triangles, more often in one direction.
        non_manifold_edges: usize,
    },
    /// The per-triangle interior flags do not match the triangles.
    #[error("{}: {flags} interior flag(s) for {triangles} triangle(s)", mesh.display())]
    FlagCount {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Number of flags given.
        flags: usize,
        /// Number of triangles.
        triangles: usize,
    },
    /// The plane has a zero or non-finite normal or a non-finite offset.
    #[error("invalid plane: normal {normal:?}, offset {offset}")]
    InvalidPlane {
        /// The normal given.
        normal: [f64; 3],
        /// The offset given.
        offset: f64,
    },
    /// The cross-section could not be triangulated, which means the surface intersects itself
    /// (its cut loops cross) or is too degenerate at this plane.
    #[error("{}: cannot cap the cross-section: {reason}", mesh.display())]
    Cap {
        /// The mesh's source path.
        mesh: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// The number of requested pieces is 0 or above the limit.
    #[error("{requested} pieces requested; fracture makes 1 to {max} pieces")]
    PieceCount {
        /// Pieces requested.
        requested: usize,
        /// The limit ([`super::voronoi::MAX_PIECES`]).
        max: usize,
    },
    /// A Voronoi site is not finite.
    #[error("site {index} is not finite")]
    InvalidSite {
        /// Index of the site.
        index: usize,
    },
    /// Two Voronoi sites coincide, so their bisector is undefined.
    #[error("sites {first} and {second} coincide")]
    DuplicateSites {
        /// Index of the first site.
        first: usize,
        /// Index of the second site.
        second: usize,
    },
    /// Random sites could not be placed inside the mesh (it encloses (almost) no volume).
    #[error("{}: found only {found} of {wanted} points inside the mesh after {attempts} attempts", mesh.display())]
    Sampling {
        /// The mesh's source path.
        mesh: PathBuf,
        /// Points wanted.
        wanted: usize,
        /// Points found.
        found: usize,
        /// Candidates tried.
        attempts: usize,
    },
}
