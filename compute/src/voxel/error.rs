//! Errors of the voxelizers: each names the limit or the triangle at fault.

use crate::gpu::GpuError;

/// Why a mesh could not be voxelized.
#[derive(Debug, thiserror::Error)]
pub enum VoxelError {
    /// The resolution is outside what the keys and counts support.
    #[error("voxel resolution {resolution} is outside 1..={max}")]
    Resolution {
        /// The resolution asked for.
        resolution: u32,
        /// [`super::MAX_RESOLUTION`].
        max: u32,
    },
    /// A triangle names a vertex that does not exist.
    #[error("triangle {triangle} uses vertex {vertex} but the mesh has {vertices} vertices")]
    VertexIndex {
        /// Index of the triangle.
        triangle: usize,
        /// The bad vertex index.
        vertex: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// More candidates than the GPU primitives can count.
    #[error("voxelizing {triangles} triangles at resolution {resolution} needs {count} {what}, above the limit of {limit}; use a lower resolution")]
    TooMany {
        /// Columns or voxel hits.
        what: &'static str,
        /// How many were needed.
        count: u64,
        /// The primitives' limit.
        limit: u64,
        /// Triangles in the mesh.
        triangles: usize,
        /// The resolution.
        resolution: u32,
    },
    /// The device failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
}
