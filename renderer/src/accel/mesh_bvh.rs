//! The bottom level: one CWBVH per mesh with its triangles reordered into leaf order.

use super::gpu_types::{GpuTriangle, GpuTriangleNormals, GpuTriangleUvs};
use super::normals::{corner_normals, encode_octahedral};
use super::tangents::corner_tangents;
use crate::mesh::Mesh;
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::triangle::Triangle;
use std::time::{Duration, Instant};

/// Largest angle between neighbouring faces that is still smoothed by the shading normals.
pub const CREASE_ANGLE_DEG: f32 = 50.0;

/// A mesh's BVH and its GPU triangle records.
pub struct MeshBvh {
    /// obvhs's BVH over the mesh's triangles, in object space.
    pub bvh: CwBvh,
    /// obvhs triangles in mesh order (what the CPU reference intersects).
    pub triangles: Vec<Triangle>,
    /// Triangle records in leaf order: record `i` is mesh triangle `bvh.primitive_indices[i]`.
    pub gpu_triangles: Vec<GpuTriangle>,
    /// Corner shading normals in the same leaf order.
    pub gpu_normals: Vec<GpuTriangleNormals>,
    /// Corner texture coordinates and tangents in the same leaf order; empty when the mesh
    /// has no texture coordinates.
    pub gpu_uvs: Vec<GpuTriangleUvs>,
    /// Wall time of the build (BVH only, not the records).
    pub build_time: Duration,
}

impl MeshBvh {
    /// Builds the BVH of `mesh` with [`super::build_params`].
    pub fn build(mesh: &Mesh) -> MeshBvh {
        let p = &mesh.positions;
        let triangles: Vec<Triangle> = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| p[i as usize].into());
                Triangle {
                    v0: a,
                    v1: b,
                    v2: c,
                }
            })
            .collect();
        let start = Instant::now();
        let mut core = Duration::ZERO;
        let bvh = build_cwbvh_from_tris(&triangles, super::build_params(), &mut core);
        let build_time = start.elapsed();
        let normals = corner_normals(mesh, CREASE_ANGLE_DEG);
        let gpu_triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| {
                let t = &triangles[i as usize];
                GpuTriangle::new([t.v0.into(), t.v1.into(), t.v2.into()], i)
            })
            .collect();
        let gpu_normals = bvh
            .primitive_indices
            .iter()
            .map(|&i| {
                let n = normals[i as usize];
                GpuTriangleNormals {
                    corners: n.map(encode_octahedral),
                    pad: 0,
                }
            })
            .collect();
        let gpu_uvs = match (corner_tangents(mesh, &normals), &mesh.uvs) {
            (Some(tangents), Some(uvs)) => bvh
                .primitive_indices
                .iter()
                .map(|&i| {
                    let tri = mesh.triangles[i as usize];
                    let t = tangents[i as usize];
                    GpuTriangleUvs {
                        uv: tri.map(|v| uvs[v as usize].to_array()),
                        tangents: t.map(|c| encode_octahedral(c.truncate())),
                        flipped: (0..3).filter(|&k| t[k].w < 0.0).map(|k| 1 << k).sum(),
                    }
                })
                .collect(),
            _ => Vec::new(),
        };
        MeshBvh {
            bvh,
            triangles,
            gpu_triangles,
            gpu_normals,
            gpu_uvs,
            build_time,
        }
    }
}
