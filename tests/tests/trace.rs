//! The GLSL two-level CWBVH traversal against obvhs's CPU traversal of the same BVHs.

use glam::{Affine3A, Quat, Vec3};
use lazysolid_renderer::accel::{
    DeviceBvh, GpuRay, GpuRayHit, InstanceDesc, QueryKind, RayQueries, SceneBvh, NO_HIT,
};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::{rng, unit_mesh, with_gpu};
use rand::Rng;
use rayon::prelude::*;

/// Rays from a sphere around `center` towards random points of the box `center ± half`, and a
/// tenth in uniformly random directions (mostly misses).
fn random_rays(n: usize, seed: u64, center: Vec3, half: Vec3, radius: f32) -> Vec<GpuRay> {
    let mut r = rng(seed);
    (0..n)
        .map(|i| {
            let dir_on_sphere = loop {
                let v = Vec3::new(
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                    r.random_range(-1.0..1.0),
                );
                if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
                    break v.normalize();
                }
            };
            let origin = center + dir_on_sphere * radius;
            let target = if i % 10 == 9 {
                origin + Vec3::new(r.random(), r.random(), r.random()) - 0.5
            } else {
                center
                    + half
                        * Vec3::new(
                            r.random_range(-1.0..1.0),
                            r.random_range(-1.0..1.0),
                            r.random_range(-1.0..1.0),
                        )
            };
            GpuRay {
                origin: origin.into(),
                tmin: 0.0,
                direction: (target - origin).normalize().into(),
                tmax: f32::INFINITY,
            }
        })
        .collect()
}

#[derive(Debug, Default)]
struct Agreement {
    rays: usize,
    hits: usize,
    exact: usize,
    /// Same distance, different (adjacent) triangle: a ray through a shared edge.
    edge_ties: usize,
    disagreements: Vec<(usize, GpuRayHit, GpuRayHit)>,
}

fn compare(gpu: &[GpuRayHit], cpu: &[GpuRayHit]) -> Agreement {
    let mut a = Agreement {
        rays: gpu.len(),
        ..Default::default()
    };
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        assert_eq!(g.overflow, 0, "ray {i}: the traversal stack overflowed");
        if c.instance != NO_HIT {
            a.hits += 1;
        }
        let same_t = (g.t == c.t) || ((g.t - c.t).abs() <= 1e-5 * c.t.abs().max(1e-3));
        if g.instance == c.instance && g.triangle == c.triangle && same_t {
            a.exact += 1;
        } else if g.instance != NO_HIT && c.instance != NO_HIT && same_t {
            a.edge_ties += 1;
        } else {
            a.disagreements.push((i, *g, *c));
        }
    }
    a
}

fn check(a: &Agreement, what: &str) {
    println!(
        "{what}: {} rays, {} hits, {} exact, {} edge ties, {} disagreements",
        a.rays,
        a.hits,
        a.exact,
        a.edge_ties,
        a.disagreements.len()
    );
    // A ray through a shared edge may report either triangle; those are rare and equidistant.
    assert!(
        a.edge_ties * 10_000 <= a.rays,
        "{what}: too many edge ties: {}",
        a.edge_ties
    );
    // Hit/miss or distance disagreements may only come from rays grazing an edge, where the
    // GPU's fused multiply-adds round differently from the CPU's SSE code.
    assert!(
        a.disagreements.len() * 100_000 <= a.rays,
        "{what}: {} disagreements, first: {:?}",
        a.disagreements.len(),
        &a.disagreements[..a.disagreements.len().min(5)]
    );
    assert!(a.hits * 4 > a.rays, "{what}: too few rays hit to test much");
}

#[test]
fn gpu_traversal_matches_obvhs_on_a_million_rays_against_armadillo() {
    let mesh = unit_mesh("armadillo.off");
    let bvh = SceneBvh::build(
        &[&mesh],
        &[InstanceDesc {
            mesh: 0,
            material: 0,
            transform: Affine3A::IDENTITY,
        }],
    );
    let rays = random_rays(1 << 20, 7, Vec3::splat(0.5), Vec3::splat(0.45), 1.5);
    let cpu: Vec<GpuRayHit> = rays.par_iter().map(|r| bvh.trace_cpu(r)).collect();
    let gpu = with_gpu(|gpu| {
        let device = DeviceBvh::upload(gpu, &bvh).unwrap();
        let q = RayQueries::new(gpu).unwrap();
        q.run(gpu, &device, &rays, QueryKind::Closest).unwrap()
    });
    let a = compare(&gpu, &cpu);
    check(&a, "armadillo, 1 instance");
    // Barycentrics locate the hit point on the reported triangle.
    let positions = &mesh.positions;
    for (r, h) in rays.iter().zip(&gpu).step_by(97) {
        if h.instance == NO_HIT {
            continue;
        }
        let t = mesh.triangles[h.triangle as usize].map(|i| positions[i as usize]);
        let p = t[0] * (1.0 - h.u - h.v) + t[1] * h.u + t[2] * h.v;
        let q = Vec3::from(r.origin) + Vec3::from(r.direction) * h.t;
        assert!((p - q).length() < 1e-4, "hit point {p} vs ray point {q}");
    }
}

#[test]
fn two_level_traversal_matches_the_cpu_over_many_transformed_instances() {
    let bunny = unit_mesh("bunny00.off");
    let dragon = unit_mesh("ChineseDragon-10kv.off");
    let mut r = rng(11);
    let instances: Vec<InstanceDesc> = (0..40)
        .map(|i| {
            let axis = Vec3::new(r.random(), r.random(), r.random()).normalize() + 0.01;
            InstanceDesc {
                mesh: i % 2,
                material: i as u32,
                transform: Affine3A::from_scale_rotation_translation(
                    Vec3::splat(r.random_range(0.3..1.2)),
                    Quat::from_axis_angle(
                        axis.normalize(),
                        r.random_range(0.0..std::f32::consts::TAU),
                    ),
                    Vec3::new(
                        r.random_range(-2.0..2.0),
                        r.random_range(-2.0..2.0),
                        r.random_range(-2.0..2.0),
                    ),
                ),
            }
        })
        .collect();
    let bvh = SceneBvh::build(&[&bunny, &dragon], &instances);
    let rays = random_rays(200_000, 8, Vec3::splat(0.0), Vec3::splat(2.0), 5.0);
    let cpu: Vec<GpuRayHit> = rays.par_iter().map(|r| bvh.trace_cpu(r)).collect();
    let (closest, any) = with_gpu(|gpu| {
        let device = DeviceBvh::upload(gpu, &bvh).unwrap();
        let q = RayQueries::new(gpu).unwrap();
        (
            q.run(gpu, &device, &rays, QueryKind::Closest).unwrap(),
            q.run(gpu, &device, &rays, QueryKind::Any).unwrap(),
        )
    });
    let a = compare(&closest, &cpu);
    check(&a, "40 instances of 2 meshes");
    // Any-hit queries agree with closest-hit queries on whether something is hit, and never
    // report a hit closer than the closest one.
    let mut occlusion_mismatch = 0;
    for (c, h) in closest.iter().zip(&any) {
        if (c.instance == NO_HIT) != (h.instance == NO_HIT) {
            occlusion_mismatch += 1;
        } else if c.instance != NO_HIT {
            assert!(
                h.t >= c.t,
                "any hit at {} before the closest at {}",
                h.t,
                c.t
            );
        }
    }
    assert_eq!(occlusion_mismatch, 0);
}

#[test]
fn a_single_triangle_scene_and_a_ray_starting_past_the_hit() {
    let mesh = Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        triangles: vec![[0, 1, 2]],
        uvs: None,
        source: "triangle".into(),
    };
    let bvh = SceneBvh::build(
        &[&mesh],
        &[InstanceDesc {
            mesh: 0,
            material: 0,
            transform: Affine3A::from_translation(Vec3::new(0.0, 0.0, -1.0)),
        }],
    );
    let ray = |tmin: f32, tmax: f32| GpuRay {
        origin: [0.25, 0.25, 1.0],
        tmin,
        direction: [0.0, 0.0, -1.0],
        tmax,
    };
    let rays = [ray(0.0, 10.0), ray(2.5, 10.0), ray(0.0, 1.5)];
    let hits = with_gpu(|gpu| {
        let device = DeviceBvh::upload(gpu, &bvh).unwrap();
        RayQueries::new(gpu)
            .unwrap()
            .run(gpu, &device, &rays, QueryKind::Closest)
            .unwrap()
    });
    assert_eq!(hits[0].instance, 0);
    assert_eq!(hits[0].triangle, 0);
    assert!((hits[0].t - 2.0).abs() < 1e-6);
    assert!((hits[0].u - 0.25).abs() < 1e-6 && (hits[0].v - 0.25).abs() < 1e-6);
    assert_eq!(hits[1].instance, NO_HIT, "tmin past the hit");
    assert_eq!(hits[2].instance, NO_HIT, "tmax before the hit");
    for (r, h) in rays.iter().zip(&hits) {
        assert_eq!(bvh.trace_cpu(r).instance, h.instance);
    }
}
