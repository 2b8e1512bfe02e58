//! The CPU reference traversal: obvhs's own `ray_traverse` over the same two levels, used to
//! check the GLSL traversal and as the CPU baseline of `lazysolid bench trace`.

use super::gpu_types::{GpuRay, GpuRayHit};
use super::scene_bvh::SceneBvh;
use super::NO_HIT;
use glam::Vec3A;
use obvhs::ray::{Ray, RayHit};

impl SceneBvh {
    /// Closest hit of `ray`, or a hit with `instance == NO_HIT` and `t = +∞`.
    pub fn trace_cpu(&self, ray: &GpuRay) -> GpuRayHit {
        let world = Ray::new(
            Vec3A::from_array(ray.origin),
            Vec3A::from_array(ray.direction),
            ray.tmin,
            ray.tmax,
        );
        let mut best = GpuRayHit {
            t: f32::INFINITY,
            instance: NO_HIT,
            triangle: NO_HIT,
            ..Default::default()
        };
        let mut tlas_hit = RayHit::none();
        self.tlas.ray_traverse(world, &mut tlas_hit, |r, id| {
            let instance = self.tlas.primitive_indices[id] as usize;
            let desc = &self.instances[instance];
            let inv = &self.world_to_object[instance];
            let local = Ray::new(
                inv.transform_point3a(r.origin),
                inv.transform_vector3a(r.direction),
                r.tmin,
                r.tmax,
            );
            let mesh = &self.meshes[desc.mesh];
            let mut hit = RayHit::none();
            if mesh.bvh.ray_traverse(local, &mut hit, |lr, tri| {
                mesh.triangles[mesh.bvh.primitive_indices[tri] as usize].intersect(lr)
            }) {
                let triangle = mesh.bvh.primitive_indices[hit.primitive_id as usize];
                let bary = barycentrics(&mesh.triangles[triangle as usize], &local);
                best = GpuRayHit {
                    t: hit.t,
                    instance: instance as u32,
                    triangle,
                    u: bary[0],
                    v: bary[1],
                    overflow: 0,
                    pad: [0; 2],
                };
                hit.t
            } else {
                f32::INFINITY
            }
        });
        best
    }
}

/// Barycentric weights of vertices 1 and 2 at the ray's crossing of the triangle's plane,
/// computed as the GPU computes them.
fn barycentrics(t: &obvhs::triangle::Triangle, ray: &Ray) -> [f32; 2] {
    let e1 = t.v0 - t.v1;
    let e2 = t.v2 - t.v0;
    let n = e1.cross(e2);
    let r = ray.direction.cross(t.v0 - ray.origin);
    let inv_det = 1.0 / n.dot(ray.direction);
    [r.dot(e2) * inv_det, r.dot(e1) * inv_det]
}
