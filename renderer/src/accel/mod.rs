//! Ray-tracing acceleration: obvhs compressed wide BVHs (CWBVH, 8-wide, 80-byte nodes) built
//! on the CPU, one per mesh (the bottom level) plus one over the instances (the top level),
//! uploaded as-is for the GLSL traversal in `glsl/include/render/cwbvh.glsl`.
//!
//! Two levels because the cut and explosion scenes instance one mesh per fragment: moving a
//! fragment only rebuilds the small top level. The CPU traversal in [`cpu_trace`] walks the same
//! BVHs with obvhs's own `ray_traverse`, so GPU results are checked against an independent
//! traversal of the same data.

pub mod cpu_trace;
mod device;
mod gpu_types;
mod mesh_bvh;
mod normals;
pub(crate) mod ray_queries;
mod scene_bvh;
mod tangents;

pub use device::DeviceBvh;
pub use gpu_types::{
    GpuInstance, GpuRay, GpuRayHit, GpuTriangle, GpuTriangleNormals, GpuTriangleUvs, NO_UVS,
};
pub use mesh_bvh::MeshBvh;
pub use normals::corner_normals;
pub use ray_queries::{QueryKind, RayQueries, CWBVH_SHARED_BYTES};
pub use scene_bvh::{InstanceDesc, SceneBvh};
pub use tangents::corner_tangents;

/// Build quality of every BVH of a render: obvhs's `medium_build` preset (PLOC plus
/// reinsertion). Measured on this project's meshes it traces faster than the faster presets
/// for the build-time cost of a fraction of a frame.
pub fn build_params() -> obvhs::BvhBuildParams {
    obvhs::BvhBuildParams::medium_build()
}

/// Marks "no hit" in [`GpuRayHit::instance`] and the CPU reference; defined with the
/// constants shared with GLSL, which `render/cwbvh.glsl` and `trace_rays.comp` write.
pub use crate::shader_constants::NO_HIT;
