//! The two-level BVH of a scene: mesh BVHs (bottom) and a BVH over instance bounds (top).

use super::gpu_types::{affine_rows, GpuInstance, NO_UVS};
use super::mesh_bvh::MeshBvh;
use crate::mesh::Mesh;
use crate::scene::Scene;
use glam::{Affine3A, Vec3, Vec3A};
use obvhs::aabb::Aabb;
use obvhs::cwbvh::{builder::build_cwbvh, node::CwBvhNode, CwBvh};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// A placed mesh as the BVH needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstanceDesc {
    /// Index of the mesh.
    pub mesh: usize,
    /// Material index (carried to the GPU record).
    pub material: u32,
    /// Object-to-world transform (invertible).
    pub transform: Affine3A,
}

/// Both levels, ready to upload or to trace on the CPU.
pub struct SceneBvh {
    /// One BVH per mesh.
    pub meshes: Vec<MeshBvh>,
    /// The placed meshes.
    pub instances: Vec<InstanceDesc>,
    /// Inverse of each instance's transform, computed once: rays enter object space with it
    /// on the GPU and in the CPU reference.
    pub world_to_object: Vec<Affine3A>,
    /// The top level over the world bounds of the instances; its primitive ids are instance
    /// indices through `tlas.primitive_indices`.
    pub tlas: CwBvh,
    /// Wall time of building every mesh BVH.
    pub blas_time: Duration,
    /// Wall time of building the top level.
    pub tlas_time: Duration,
}

impl SceneBvh {
    /// Builds the BVHs of `meshes` (in parallel) and the top level over `instances`.
    ///
    /// # Panics
    /// When an instance names a mesh that does not exist or when there is no instance: scenes
    /// are validated before they get here.
    pub fn build(meshes: &[&Mesh], instances: &[InstanceDesc]) -> SceneBvh {
        assert!(!instances.is_empty(), "a scene needs at least one instance");
        let start = Instant::now();
        let mesh_bvhs: Vec<MeshBvh> = meshes.par_iter().map(|m| MeshBvh::build(m)).collect();
        let blas_time = start.elapsed();
        let start = Instant::now();
        let bounds: Vec<Aabb> = instances
            .iter()
            .map(|i| world_bounds(&mesh_bvhs[i.mesh].bvh.total_aabb, &i.transform))
            .collect();
        let mut core = Duration::ZERO;
        let tlas = build_cwbvh(&bounds, super::build_params(), &mut core);
        let tlas_time = start.elapsed();
        SceneBvh {
            meshes: mesh_bvhs,
            instances: instances.to_vec(),
            world_to_object: instances.iter().map(|i| i.transform.inverse()).collect(),
            tlas,
            blas_time,
            tlas_time,
        }
    }

    /// Builds the BVHs of a loaded scene.
    pub fn from_scene(scene: &Scene) -> SceneBvh {
        let meshes: Vec<&Mesh> = scene.meshes.iter().map(|m| &m.mesh).collect();
        let instances: Vec<InstanceDesc> = scene
            .instances
            .iter()
            .map(|i| InstanceDesc {
                mesh: i.mesh,
                material: i.material as u32,
                transform: i.transform,
            })
            .collect();
        SceneBvh::build(&meshes, &instances)
    }

    /// Moves the instances to `transforms` (one per instance, same meshes): only the top
    /// level is rebuilt, which is what an animation frame costs.
    ///
    /// # Panics
    /// When `transforms` does not have one transform per instance.
    pub fn set_transforms(&mut self, transforms: &[Affine3A]) {
        assert_eq!(
            transforms.len(),
            self.instances.len(),
            "one transform per instance"
        );
        let start = Instant::now();
        for (i, &t) in self.instances.iter_mut().zip(transforms) {
            i.transform = t;
        }
        let bounds: Vec<Aabb> = self
            .instances
            .iter()
            .map(|i| world_bounds(&self.meshes[i.mesh].bvh.total_aabb, &i.transform))
            .collect();
        let mut core = Duration::ZERO;
        self.tlas = build_cwbvh(&bounds, super::build_params(), &mut core);
        self.world_to_object = transforms.iter().map(|t| t.inverse()).collect();
        self.tlas_time = start.elapsed();
    }

    /// All nodes in one array: the top level first, then each mesh's BVH (at
    /// [`SceneBvh::node_offsets`]).
    pub fn packed_nodes(&self) -> Vec<CwBvhNode> {
        let mut nodes = self.tlas.nodes.clone();
        for m in &self.meshes {
            nodes.extend_from_slice(&m.bvh.nodes);
        }
        nodes
    }

    /// Offset of each mesh's first node in [`SceneBvh::packed_nodes`].
    pub fn node_offsets(&self) -> Vec<u32> {
        let mut offsets = Vec::with_capacity(self.meshes.len());
        let mut n = self.tlas.nodes.len() as u32;
        for m in &self.meshes {
            offsets.push(n);
            n += m.bvh.nodes.len() as u32;
        }
        offsets
    }

    /// Offset of each mesh's first triangle in the concatenated triangle records.
    pub fn triangle_offsets(&self) -> Vec<u32> {
        let mut offsets = Vec::with_capacity(self.meshes.len());
        let mut n = 0u32;
        for m in &self.meshes {
            offsets.push(n);
            n += m.gpu_triangles.len() as u32;
        }
        offsets
    }

    /// Offset of each mesh's first record in the concatenated UV records, [`NO_UVS`] for a
    /// mesh without texture coordinates.
    pub fn uv_offsets(&self) -> Vec<u32> {
        let mut n = 0u32;
        self.meshes
            .iter()
            .map(|m| {
                if m.gpu_uvs.is_empty() {
                    NO_UVS
                } else {
                    n += m.gpu_uvs.len() as u32;
                    n - m.gpu_uvs.len() as u32
                }
            })
            .collect()
    }

    /// The GPU records of the instances.
    pub fn gpu_instances(&self) -> Vec<GpuInstance> {
        let node_offsets = self.node_offsets();
        let tri_offsets = self.triangle_offsets();
        let uv_offsets = self.uv_offsets();
        self.instances
            .iter()
            .zip(&self.world_to_object)
            .map(|(i, inv)| GpuInstance {
                world_to_object: affine_rows(inv),
                object_to_world: affine_rows(&i.transform),
                node_offset: node_offsets[i.mesh],
                triangle_offset: tri_offsets[i.mesh],
                material: i.material,
                mesh: i.mesh as u32,
                uv_offset: uv_offsets[i.mesh],
                pad: [0; 3],
            })
            .collect()
    }

    /// Total triangles over all instances (what a flat BVH would hold).
    pub fn instanced_triangles(&self) -> u64 {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh].triangles.len() as u64)
            .sum()
    }

    /// World-space bounds of the whole scene.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        (
            self.tlas.total_aabb.min.into(),
            self.tlas.total_aabb.max.into(),
        )
    }
}

/// Bounds of the eight transformed corners of `b`.
fn world_bounds(b: &Aabb, t: &Affine3A) -> Aabb {
    let mut out = Aabb::INVALID;
    for c in 0..8 {
        let p = Vec3A::new(
            if c & 1 == 0 { b.min.x } else { b.max.x },
            if c & 2 == 0 { b.min.y } else { b.max.y },
            if c & 4 == 0 { b.min.z } else { b.max.z },
        );
        out.extend(t.transform_point3a(p));
    }
    out
}
