//! The GPU voxelizer against the plain-Rust one: surface voxels and interpolation voxels, key
//! for key, on real meshes at several resolutions (powers of two and not) and on edge cases.

use glam::Vec3;
use lazysolid_compute::hash::morton_decode;
use lazysolid_compute::voxel::*;
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::{unit_mesh, with_gpu};

fn check(v: &mut Voxelizer, m: &Mesh, resolution: u32) {
    let cpu = surface_voxels_cpu(&m.positions, &m.triangles, resolution);
    let gpu = v
        .surface(&m.positions, &m.triangles, resolution)
        .unwrap()
        .read()
        .unwrap();
    assert!(!cpu.is_empty());
    assert_eq!(gpu.len(), cpu.len(), "{:?} R={resolution}", m.source);
    assert!(gpu == cpu, "{:?} R={resolution}: keys differ", m.source);
    let cpu_i = interpolation_voxels_cpu(&m.positions, &m.triangles, resolution);
    let gpu_i = v
        .interpolation(&m.positions, &m.triangles, resolution)
        .unwrap()
        .read()
        .unwrap();
    assert_eq!(gpu_i.len(), cpu_i.len(), "{:?} R={resolution}", m.source);
    assert!(
        gpu_i == cpu_i,
        "{:?} R={resolution}: interpolation keys differ",
        m.source
    );
    // Every surface voxel is an interpolation voxel, and the layer is thicker.
    let set: std::collections::HashSet<u64> = cpu_i.iter().copied().collect();
    assert!(cpu.iter().all(|k| set.contains(k)));
    assert!(cpu_i.len() > cpu.len());
}

#[test]
fn bunny_and_armadillo_match_the_cpu_voxelizer() {
    with_gpu(|gpu| {
        let mut v = Voxelizer::new(gpu).unwrap();
        let bunny = unit_mesh("bunny00.off");
        for r in [64, 100, 128, 256] {
            check(&mut v, &bunny, r);
        }
        let armadillo = unit_mesh("armadillo.off");
        for r in [64, 97, 256] {
            check(&mut v, &armadillo, r);
        }
    });
}

#[test]
fn single_triangles_and_edge_cases() {
    with_gpu(|gpu| {
        let mut v = Voxelizer::new(gpu).unwrap();
        let cases: Vec<[Vec3; 3]> = vec![
            // A large slanted triangle across the whole cube (column walk, not the box).
            [
                Vec3::new(0.0, 0.0, 0.1),
                Vec3::new(1.0, 0.1, 0.9),
                Vec3::new(0.2, 1.0, 0.5),
            ],
            // Axis-aligned, lying exactly on voxel faces.
            [
                Vec3::new(0.25, 0.25, 0.5),
                Vec3::new(0.75, 0.25, 0.5),
                Vec3::new(0.25, 0.75, 0.5),
            ],
            // Tiny, inside one voxel; and touching the cube's faces and corners.
            [
                Vec3::new(0.501, 0.502, 0.503),
                Vec3::new(0.5011, 0.502, 0.503),
                Vec3::new(0.501, 0.5021, 0.5031),
            ],
            [
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 1.0),
            ],
            [
                Vec3::new(1.0, 1.0, 1.0),
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(0.0, 1.0, 1.0),
            ],
            // Degenerate: a segment, and a point on a voxel corner.
            [
                Vec3::new(0.1, 0.2, 0.3),
                Vec3::new(0.9, 0.7, 0.4),
                Vec3::new(0.5, 0.45, 0.35),
            ],
            [Vec3::splat(0.5), Vec3::splat(0.5), Vec3::splat(0.5)],
            // Partly outside the unit cube.
            [
                Vec3::new(-0.5, 0.3, 0.3),
                Vec3::new(1.5, 0.35, 0.4),
                Vec3::new(0.5, 0.6, 1.7),
            ],
        ];
        for (i, t) in cases.iter().enumerate() {
            for r in [1, 2, 7, 16, 33, 64] {
                let tris = [[0, 1, 2]];
                let cpu = surface_voxels_cpu(t, &tris, r);
                let gpu = v.surface(t, &tris, r).unwrap().read().unwrap();
                assert_eq!(gpu, cpu, "case {i} R={r}");
                // (A face exactly on the cube's boundary may round off a grid whose size is
                // not a power of two, in both voxelizers alike.)
                assert!(
                    !cpu.is_empty() || i == 7 || !r.is_power_of_two(),
                    "case {i} R={r}"
                );
                let cpu = interpolation_voxels_cpu(t, &tris, r);
                let gpu = v.interpolation(t, &tris, r).unwrap().read().unwrap();
                assert_eq!(gpu, cpu, "case {i} R={r} (interpolation)");
                assert!(cpu
                    .iter()
                    .all(|&k| morton_decode(k, 3).iter().all(|&c| c < r)));
            }
        }
        // The centre point of voxel corner (R/2)³ touches the 8 voxels around it.
        let p = [Vec3::splat(0.5); 3];
        assert_eq!(surface_voxels_cpu(&p, &[[0, 1, 2]], 16).len(), 8);
        // Empty meshes and bad input.
        assert!(v.surface(&[], &[], 64).unwrap().is_empty());
        assert!(matches!(
            v.surface(&[Vec3::ZERO], &[[0, 0, 1]], 64),
            Err(VoxelError::VertexIndex {
                triangle: 0,
                vertex: 1,
                ..
            })
        ));
        assert!(matches!(
            v.surface(&p, &[[0, 1, 2]], 4096),
            Err(VoxelError::Resolution {
                resolution: 4096,
                ..
            })
        ));
        assert!(matches!(
            v.surface(&p, &[[0, 1, 2]], 0),
            Err(VoxelError::Resolution { .. })
        ));
    });
}

#[test]
fn interpolation_voxels_cover_every_trilinear_footprint_on_the_surface() {
    // Sample points on the bunny's triangles: the 8 voxels a clamp-to-edge trilinear lookup
    // reads there are all interpolation voxels.
    let m = unit_mesh("bunny00.off");
    let r = 64u32;
    let keys: std::collections::HashSet<u64> =
        interpolation_voxels_cpu(&m.positions, &m.triangles, r)
            .into_iter()
            .collect();
    let mut rng = lazysolid_tests::rng(7);
    for t in m.triangles.iter().step_by(7) {
        let p = lazysolid_tests::point_on_triangle(&mut rng, t.map(|i| m.positions[i as usize]));
        let q = p * r as f32 - 0.5;
        let base = q.floor();
        for o in 0..8 {
            let c = base + Vec3::new((o & 1) as f32, ((o >> 1) & 1) as f32, (o >> 2) as f32);
            let c = c.clamp(Vec3::ZERO, Vec3::splat(r as f32 - 1.0)).as_uvec3();
            let k = lazysolid_compute::hash::morton_encode(c.to_array(), 3);
            assert!(keys.contains(&k), "{p} needs {c}");
        }
    }
}

/// Union and difference of key sets on the device equal their CPU references: overlapping,
/// disjoint, nested, empty and equal sets, and keys using the top bit the tag leaves.
#[test]
fn key_set_union_and_difference_equal_the_cpu_references() {
    use rand::Rng;
    let mut r = lazysolid_tests::rng(17);
    let mut set = |n: usize, bits: u32| -> Vec<u64> {
        let mut v: Vec<u64> = (0..n).map(|_| r.random::<u64>() >> (64 - bits)).collect();
        v.sort_unstable();
        v.dedup();
        v
    };
    let a = set(5000, 18);
    let b = set(4000, 18);
    let wide = set(300, 63);
    let cases: Vec<(&str, Vec<u64>, Vec<u64>, u32)> = vec![
        ("overlapping", a.clone(), b.clone(), 18),
        ("disjoint", vec![1, 3, 5], vec![2, 4, 6], 3),
        ("nested", a.clone(), a[100..900].to_vec(), 18),
        ("a empty", vec![], b.clone(), 18),
        ("b empty", a.clone(), vec![], 18),
        ("both empty", vec![], vec![], 18),
        ("equal", b.clone(), b.clone(), 18),
        ("63 bits", wide.clone(), wide[..150].to_vec(), 63),
    ];
    with_gpu(|gpu| {
        let mut sets = KeySets::new(gpu).unwrap();
        for (name, a, b, bits) in &cases {
            let ka = VoxelKeys::from_sorted(gpu, "a", a).unwrap();
            let kb = VoxelKeys::from_sorted(gpu, "b", b).unwrap();
            let u = sets.union(&ka, &kb, *bits).unwrap().read().unwrap();
            assert_eq!(u, union_cpu(a, b), "{name}: union");
            let d = sets.difference(&ka, &kb, *bits).unwrap().read().unwrap();
            assert_eq!(d, difference_cpu(a, b), "{name}: a \\ b");
            let d = sets.difference(&kb, &ka, *bits).unwrap().read().unwrap();
            assert_eq!(d, difference_cpu(b, a), "{name}: b \\ a");
        }
        let k = VoxelKeys::from_sorted(gpu, "k", &[1]).unwrap();
        assert!(
            sets.union(&k, &k, 64).is_err(),
            "64-bit keys leave no tag bit"
        );
    });
}
