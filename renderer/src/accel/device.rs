//! The two-level BVH on the device: one owner of its buffers, bound by name by every kernel
//! that includes `render/cwbvh.glsl`.

use super::gpu_types::{GpuInstance, GpuTriangle, GpuTriangleNormals, GpuTriangleUvs};
use super::scene_bvh::SceneBvh;
use lazysolid_compute::gpu::{BufferArg, Gpu, GpuBuffer, GpuResult};
use obvhs::cwbvh::node::CwBvhNode;

/// The uploaded BVH buffers.
pub struct DeviceBvh {
    nodes: GpuBuffer<CwBvhNode>,
    tlas_instances: GpuBuffer<u32>,
    triangles: GpuBuffer<GpuTriangle>,
    normals: GpuBuffer<GpuTriangleNormals>,
    uvs: GpuBuffer<GpuTriangleUvs>,
    instances: GpuBuffer<GpuInstance>,
}

impl DeviceBvh {
    /// Uploads `bvh`.
    ///
    /// # Errors
    /// A buffer over a device limit (the error names the buffer and the limit).
    pub fn upload(gpu: &Gpu, bvh: &SceneBvh) -> GpuResult<DeviceBvh> {
        let nodes = bvh.packed_nodes();
        let triangles: Vec<GpuTriangle> = bvh
            .meshes
            .iter()
            .flat_map(|m| m.gpu_triangles.iter().copied())
            .collect();
        let normals: Vec<GpuTriangleNormals> = bvh
            .meshes
            .iter()
            .flat_map(|m| m.gpu_normals.iter().copied())
            .collect();
        let mut uvs: Vec<GpuTriangleUvs> = bvh
            .meshes
            .iter()
            .flat_map(|m| m.gpu_uvs.iter().copied())
            .collect();
        if uvs.is_empty() {
            // A binding needs a buffer: one record nothing refers to.
            uvs.push(GpuTriangleUvs::default());
        }
        Ok(DeviceBvh {
            nodes: GpuBuffer::from_slice(gpu, "bvh nodes", &nodes)?,
            tlas_instances: GpuBuffer::from_slice(
                gpu,
                "bvh top-level primitives",
                &bvh.tlas.primitive_indices,
            )?,
            triangles: GpuBuffer::from_slice(gpu, "bvh triangles", &triangles)?,
            normals: GpuBuffer::from_slice(gpu, "bvh triangle normals", &normals)?,
            uvs: GpuBuffer::from_slice(gpu, "bvh triangle uvs", &uvs)?,
            instances: GpuBuffer::from_slice(gpu, "bvh instances", &bvh.gpu_instances())?,
        })
    }

    /// The bindings of `render/cwbvh.glsl`, by block name.
    pub fn bindings(&self) -> [(&'static str, BufferArg<'_>); 5] {
        [
            ("BvhNodes", self.nodes.arg()),
            ("BvhTlasInstances", self.tlas_instances.arg()),
            ("BvhTriangles", self.triangles.arg()),
            ("BvhTriangleNormals", self.normals.arg()),
            ("BvhInstances", self.instances.arg()),
        ]
    }

    /// The corners' texture coordinates and tangents (`BvhTriangleUvs`, declared by the
    /// kernels that shade with them, not by every traversal).
    pub fn uv_binding(&self) -> (&'static str, BufferArg<'_>) {
        ("BvhTriangleUvs", self.uvs.arg())
    }

    /// Exact GPU bytes of the BVH.
    pub fn bytes(&self) -> u64 {
        self.nodes.bytes()
            + self.tlas_instances.bytes()
            + self.triangles.bytes()
            + self.normals.bytes()
            + self.uvs.bytes()
            + self.instances.bytes()
    }
}
