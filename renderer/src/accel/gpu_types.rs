//! The GPU records of the two-level BVH and of ray queries, laid out exactly as the GLSL of
//! `glsl/include/render/cwbvh.glsl` reads them (scalar layout; sizes asserted below).

use bytemuck::{Pod, Zeroable};
use glam::{Affine3A, Vec3};

/// One triangle in BVH leaf order, stored as `v0`, `v0 − v1` and `v2 − v0` so that the GPU
/// intersection computes bit for bit what obvhs's `Triangle::intersect` computes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// First vertex (object space).
    pub v0: [f32; 3],
    /// Index of the triangle in its mesh (leaf order is the BVH's, not the mesh's).
    pub mesh_triangle: u32,
    /// `v0 − v1`.
    pub e1: [f32; 3],
    /// Unused (alignment to 16 bytes).
    pub pad0: u32,
    /// `v2 − v0`.
    pub e2: [f32; 3],
    /// Unused (alignment to 16 bytes).
    pub pad1: u32,
}

impl GpuTriangle {
    /// The record of triangle `index` with vertices `v`.
    pub fn new(v: [Vec3; 3], index: u32) -> Self {
        GpuTriangle {
            v0: v[0].into(),
            mesh_triangle: index,
            e1: (v[0] - v[1]).into(),
            pad0: 0,
            e2: (v[2] - v[0]).into(),
            pad1: 0,
        }
    }
}

/// Shading normals of a triangle's three corners, octahedron-encoded in 2×16 bits each, in
/// the same leaf order as [`GpuTriangle`]. Kept apart from the triangles so that traversal
/// reads 48 bytes per triangle, not 64.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangleNormals {
    /// Octahedral normals of corners 0, 1, 2.
    pub corners: [u32; 3],
    /// Unused (alignment to 16 bytes).
    pub pad: u32,
}

/// Texture coordinates and MikkTSpace tangents of a triangle's three corners, in the same leaf
/// order as [`GpuTriangle`], only for meshes that have coordinates (an instance finds its
/// mesh's first record at [`GpuInstance::uv_offset`]): a scene without them uploads none.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangleUvs {
    /// Texture coordinates of corners 0, 1, 2.
    pub uv: [[f32; 2]; 3],
    /// Octahedral unit tangents of corners 0, 1, 2.
    pub tangents: [u32; 3],
    /// Bit k set: corner k's bitangent is −(n × t) (a mirrored UV layout).
    pub flipped: u32,
}

/// [`GpuInstance::uv_offset`] of an instance whose mesh has no texture coordinates; defined with
/// the constants shared with GLSL, which `path_trace.comp` compares the offset with.
pub use crate::shader_constants::NO_UVS;

/// A placed mesh as the traversal and the shading kernels see it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuInstance {
    /// Rows of the 3×4 world-to-object matrix (rays are moved into object space, unnormalized,
    /// so distances along them stay world distances).
    pub world_to_object: [[f32; 4]; 3],
    /// Rows of the 3×4 object-to-world matrix.
    pub object_to_world: [[f32; 4]; 3],
    /// First node of this mesh's BVH in the shared node buffer.
    pub node_offset: u32,
    /// First triangle of this mesh in the shared triangle buffer.
    pub triangle_offset: u32,
    /// Material index.
    pub material: u32,
    /// Mesh index.
    pub mesh: u32,
    /// First [`GpuTriangleUvs`] of this mesh, [`NO_UVS`] when it has no texture coordinates.
    pub uv_offset: u32,
    /// Unused (alignment to 16 bytes).
    pub pad: [u32; 3],
}

/// Rows of the 3×4 matrix of `a`.
pub(crate) fn affine_rows(a: &Affine3A) -> [[f32; 4]; 3] {
    let m = a.matrix3;
    let t = a.translation;
    [
        [m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x],
        [m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y],
        [m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z],
    ]
}

/// A ray query: origin, direction and the accepted distance range.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuRay {
    /// Origin (world space).
    pub origin: [f32; 3],
    /// Smallest accepted distance.
    pub tmin: f32,
    /// Direction (need not be normalized; distances are in its units).
    pub direction: [f32; 3],
    /// Largest accepted distance.
    pub tmax: f32,
}

/// The closest hit of a [`GpuRay`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuRayHit {
    /// Distance (`+∞` on a miss).
    pub t: f32,
    /// Instance hit, [`super::NO_HIT`] on a miss.
    pub instance: u32,
    /// Triangle of the instance's mesh (mesh order).
    pub triangle: u32,
    /// Barycentric weight of vertex 1 (vertex 2's is in `v`).
    pub u: f32,
    /// Barycentric weight of vertex 2.
    pub v: f32,
    /// 1 when the traversal ran out of stack (never expected; the tests check it).
    pub overflow: u32,
    /// Unused (alignment to 16 bytes).
    pub pad: [u32; 2],
}

const _: () = assert!(std::mem::size_of::<GpuTriangle>() == 48);
const _: () = assert!(std::mem::size_of::<GpuTriangleNormals>() == 16);
const _: () = assert!(std::mem::size_of::<GpuTriangleUvs>() == 40);
const _: () = assert!(std::mem::size_of::<GpuInstance>() == 128);
const _: () = assert!(std::mem::size_of::<GpuRay>() == 32);
const _: () = assert!(std::mem::size_of::<GpuRayHit>() == 32);
const _: () = assert!(std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>() == 80);
