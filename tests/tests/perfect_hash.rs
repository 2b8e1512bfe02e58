//! Perfect spatial hashing: the CPU reference and the GPU construction on random, image and
//! voxel key sets in 2D and 3D — perfect on the keys, every key's payload found through the
//! GLSL include and the CPU lookup, absent keys rejected in unconstrained mode, |Φ| growth
//! reported, bad inputs refused, and blocked trilinear lookups equal to a dense grid's.

use glam::Vec3;
use lazysolid_compute::hash::perfect::*;
use lazysolid_compute::hash::{HashError, KeyLayout, Universe};
use lazysolid_compute::shader_constants::HASH_NOT_FOUND;
use lazysolid_compute::store::trilinear_cpu;
use lazysolid_compute::voxel::{VoxelGrid, Voxelizer};
use lazysolid_tests::{asset_exemplar, point_on_triangle, random_keys, rng, unit_mesh, with_gpu};
use std::collections::HashSet;
use std::sync::Arc;

/// Blocked and dense trilinear lookups sum the same eight products in the same order; the
/// GPU may contract them into fused multiply-adds.
const TRILINEAR_TOLERANCE: f32 = 1e-5;

fn payloads_for(keys: &[u64]) -> Vec<u32> {
    keys.iter()
        .map(|&k| (k.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 33) as u32)
        .collect()
}

/// The pixels of an exemplar brighter than its mean: a sparse 2D image.
fn image_keys(layout: KeyLayout) -> (Universe, Vec<u64>, Vec<u32>) {
    let e = lazysolid_synth::Exemplar::load(&asset_exemplar("brick.pat")).unwrap();
    let u = Universe::new_2d(e.width, e.height, layout).unwrap();
    let lum: Vec<u32> = e
        .rgb
        .iter()
        .map(|c| c.iter().map(|&v| v as u32).sum())
        .collect();
    let mean = lum.iter().sum::<u32>() / lum.len() as u32;
    let mut keys = Vec::new();
    let mut payloads = Vec::new();
    for (i, c) in e.rgb.iter().enumerate() {
        if lum[i] > mean {
            let p = [i as u32 % e.width, i as u32 / e.width, 0];
            keys.push(u.key(p));
            payloads.push(u32::from_le_bytes([c[0], c[1], c[2], 255]));
        }
    }
    (u, keys, payloads)
}

/// Surface voxels of the bunny at resolution `r`, voxelized on the GPU.
fn voxel_keys(gpu: &lazysolid_compute::gpu::Gpu, r: u32) -> (Universe, Vec<u64>) {
    let m = unit_mesh("bunny00.off");
    let mut v = Voxelizer::new(gpu).unwrap();
    let keys = v
        .surface(&m.positions, &m.triangles, r)
        .unwrap()
        .read()
        .unwrap();
    (Universe::new_3d([r; 3], KeyLayout::Morton).unwrap(), keys)
}

/// Perfect on the keys (distinct slots), every key's payload found, absent keys rejected
/// (unconstrained), and Φ sized as reported.
fn check_table(t: &PerfectHash, keys: &[u64], payloads: &[u32], absent: &[u64], what: &str) {
    let mut slots = HashSet::new();
    for (&k, &p) in keys.iter().zip(payloads) {
        let point = t.universe.point(k);
        assert!(slots.insert(t.slot(point)), "{what}: key {k} shares a slot");
        assert_eq!(t.lookup_key(k), Some(p), "{what}: key {k}");
    }
    let s = &t.sizes;
    assert!(
        (s.h as u64).pow(s.dimensions) >= keys.len() as u64,
        "{what}"
    );
    assert!(
        s.h == 1 || ((s.h - 1) as u64).pow(s.dimensions) < keys.len() as u64,
        "{what}: |H| not minimal"
    );
    assert_eq!(gcd(s.h, s.phi), 1, "{what}");
    assert!(
        t.universe.dims[..s.dimensions as usize]
            .iter()
            .all(|&d| d <= s.h * s.phi),
        "{what}"
    );
    assert_eq!(t.offsets.len(), s.offset_words(), "{what}");
    assert_eq!(t.report.attempts.last().unwrap().sizes, *s, "{what}");
    assert!(
        t.report.attempts.last().unwrap().failure.is_none(),
        "{what}"
    );
    if t.access == PerfectAccess::Unconstrained {
        for &k in absent {
            assert_eq!(t.lookup_key(k), None, "{what}: absent key {k} accepted");
        }
        assert_eq!(t.lookup_key(t.universe.key_count()), None, "{what}");
    }
}

/// Builds on both sides and checks both tables, the GPU lookups, equal-or-smaller GPU sizes
/// and a deterministic GPU construction.
fn check_both(
    kernels: &Arc<PerfectKernels>,
    u: Universe,
    keys: &[u64],
    payloads: &[u32],
    absent: &[u64],
    access: PerfectAccess,
    what: &str,
) {
    let config = PerfectConfig {
        access,
        ..Default::default()
    };
    let what = format!("{what} {} {access:?} ({} keys)", u.describe(), keys.len());
    let cpu =
        build_perfect_cpu(u, keys, payloads, config).unwrap_or_else(|e| panic!("{what}: {e}"));
    check_table(&cpu, keys, payloads, absent, &format!("{what} CPU"));
    let builder = PerfectBuilder::new(kernels);
    let gpu = builder
        .build_from_slices(u, keys, payloads, config)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let host = gpu.to_host().unwrap();
    check_table(&host, keys, payloads, absent, &format!("{what} GPU"));
    assert_eq!(host.sizes.h, cpu.sizes.h, "{what}");
    assert!(
        host.sizes.phi <= cpu.sizes.phi,
        "{what}: GPU {:?} CPU {:?}",
        host.report,
        cpu.report
    );
    // Same input, same table.
    let again = builder
        .build_from_slices(u, keys, payloads, config)
        .unwrap()
        .to_host()
        .unwrap();
    assert_eq!(again, host, "{what}: GPU construction is not deterministic");
    // GPU lookups through the GLSL include, on the GPU-built and the CPU-built table.
    let uploaded = PerfectHashGpu::upload(kernels, &cpu).unwrap();
    let mut queries = keys.to_vec();
    queries.extend_from_slice(absent);
    for (table, side, bytes) in [
        (&gpu, "GPU-built", host.bytes()),
        (&uploaded, "CPU-built", cpu.bytes()),
    ] {
        let results = table.query(&queries).unwrap();
        for (i, (&k, &r)) in queries.iter().zip(&results).enumerate() {
            if i < keys.len() {
                assert_eq!(r, payloads[i], "{what} {side}: GLSL lookup of key {k}");
            } else if access == PerfectAccess::Unconstrained {
                assert_eq!(r, HASH_NOT_FOUND, "{what} {side}: absent key {k} accepted");
            }
        }
        assert_eq!(table.bytes(), bytes, "{what} {side}: memory accounting");
    }
}

#[test]
fn random_keys_2d_and_3d_on_cpu_and_gpu() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        for (u, n) in [
            (
                Universe::new_2d(300, 200, KeyLayout::RowMajor).unwrap(),
                9000,
            ),
            (
                Universe::new_2d(1024, 1024, KeyLayout::Morton).unwrap(),
                70_000,
            ),
            (
                Universe::new_3d([40, 32, 24], KeyLayout::BitReversedMorton).unwrap(),
                6000,
            ),
            (
                Universe::new_3d([128; 3], KeyLayout::Morton).unwrap(),
                40_000,
            ),
        ] {
            let (keys, absent) = random_keys(&u, n, 2000, n as u64);
            let payloads = payloads_for(&keys);
            for access in [PerfectAccess::Constrained, PerfectAccess::Unconstrained] {
                check_both(&kernels, u, &keys, &payloads, &absent, access, "random");
            }
        }
    });
}

#[test]
fn image_and_voxel_keys_on_cpu_and_gpu() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        let (u, keys, payloads) = image_keys(KeyLayout::RowMajor);
        let absent: Vec<u64> = {
            let set: HashSet<u64> = keys.iter().copied().collect();
            (0..u.key_count())
                .filter(|k| !set.contains(k))
                .step_by(7)
                .collect()
        };
        for access in [PerfectAccess::Constrained, PerfectAccess::Unconstrained] {
            check_both(&kernels, u, &keys, &payloads, &absent, access, "image");
        }
        let (u, keys) = voxel_keys(gpu, 96);
        let payloads = payloads_for(&keys);
        let set: HashSet<u64> = keys.iter().copied().collect();
        let absent: Vec<u64> = random_keys(&u, 3000, 0, 5)
            .0
            .into_iter()
            .filter(|k| !set.contains(k))
            .collect();
        for access in [PerfectAccess::Constrained, PerfectAccess::Unconstrained] {
            check_both(
                &kernels,
                u,
                &keys,
                &payloads,
                &absent,
                access,
                "bunny voxels",
            );
        }
    });
}

#[test]
fn a_too_small_offset_table_grows_and_reports() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        let u = Universe::new_3d([64; 3], KeyLayout::Morton).unwrap();
        let (keys, _) = random_keys(&u, 5000, 0, 3);
        let payloads = payloads_for(&keys);
        let config = PerfectConfig {
            initial_phi: Some(5),
            ..Default::default()
        };
        let cpu = build_perfect_cpu(u, &keys, &payloads, config).unwrap();
        let gpu_table = PerfectBuilder::new(&kernels)
            .build_from_slices(u, &keys, &payloads, config)
            .unwrap();
        for report in [&cpu.report, &gpu_table.report] {
            assert!(report.growths() >= 1, "{report:?}");
            let (last, failed) = report.attempts.split_last().unwrap();
            assert!(last.failure.is_none());
            for (a, b) in failed.iter().zip(&report.attempts[1..]) {
                assert!(b.sizes.phi > a.sizes.phi, "{report:?}");
                assert!(
                    a.failure.as_ref().unwrap().contains("found no offset"),
                    "{a:?}"
                );
            }
        }
        check_table(&cpu, &keys, &payloads, &[], "grown CPU");
        check_table(
            &gpu_table.to_host().unwrap(),
            &keys,
            &payloads,
            &[],
            "grown GPU",
        );
        // Without room to grow, the construction fails with the last attempt's reason.
        let stuck = PerfectConfig {
            max_attempts: 1,
            ..config
        };
        for e in [
            build_perfect_cpu(u, &keys, &payloads, stuck).err().unwrap(),
            PerfectBuilder::new(&kernels)
                .build_from_slices(u, &keys, &payloads, stuck)
                .err()
                .unwrap(),
        ] {
            assert!(
                matches!(e, HashError::PerfectHashFailed { attempts: 1, .. }),
                "{e}"
            );
            assert!(e.to_string().contains("|Φ| = 5^3"), "{e}");
        }
    });
}

#[test]
fn duplicate_and_out_of_universe_keys_are_refused() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        let builder = PerfectBuilder::new(&kernels);
        let config = PerfectConfig::default();
        for u in [
            Universe::new_2d(100, 60, KeyLayout::RowMajor).unwrap(),
            Universe::new_3d([50, 40, 30], KeyLayout::Morton).unwrap(),
        ] {
            let (mut keys, _) = random_keys(&u, 1000, 0, 9);
            keys.push(keys[17]);
            keys.push(keys[400]);
            let payloads = payloads_for(&keys);
            let smallest = keys[17].min(keys[400]);
            for e in [
                build_perfect_cpu(u, &keys, &payloads, config)
                    .err()
                    .unwrap(),
                builder
                    .build_from_slices(u, &keys, &payloads, config)
                    .err()
                    .unwrap(),
            ] {
                assert!(
                    matches!(e, HashError::DuplicateKey { key, count: 2 } if key == smallest),
                    "{}: {e}",
                    u.describe()
                );
            }
            // A key past the key count, and (Morton) a key inside the power-of-two cube but
            // outside the grid.
            let (mut keys, _) = random_keys(&u, 1000, 0, 10);
            let outside = if u.dimensions == 3 {
                u.key([49, 40, 0]).max(u.key([0, 0, 31]))
            } else {
                u.key_count() + 5
            };
            keys.insert(3, outside);
            let payloads = payloads_for(&keys);
            for e in [
                build_perfect_cpu(u, &keys, &payloads, config)
                    .err()
                    .unwrap(),
                builder
                    .build_from_slices(u, &keys, &payloads, config)
                    .err()
                    .unwrap(),
            ] {
                assert!(
                    matches!(e, HashError::KeyOutsideUniverse { key, .. } if key == outside),
                    "{}: {e}",
                    u.describe()
                );
            }
        }
        // Unconstrained tables answer HASH_NOT_FOUND for absent keys, so it is no payload.
        let u = Universe::new_2d(64, 64, KeyLayout::Morton).unwrap();
        let (keys, _) = random_keys(&u, 100, 0, 11);
        let mut payloads = payloads_for(&keys);
        payloads[50] = HASH_NOT_FOUND;
        let config = PerfectConfig {
            access: PerfectAccess::Unconstrained,
            ..Default::default()
        };
        for e in [
            build_perfect_cpu(u, &keys, &payloads, config)
                .err()
                .unwrap(),
            builder
                .build_from_slices(u, &keys, &payloads, config)
                .err()
                .unwrap(),
        ] {
            assert!(matches!(e, HashError::PayloadTooLarge { .. }), "{e}");
        }
        // Mismatched lengths, and an empty key set.
        assert!(build_perfect_cpu(u, &keys, &payloads[1..], config).is_err());
        let empty = builder
            .build_from_slices(u, &[], &[], PerfectConfig::default())
            .unwrap();
        assert_eq!(empty.to_host().unwrap().sizes.slots(), 1);
    });
}

/// An RGBA8 colour per voxel (a hash): neighbouring texels differ, so any misplaced texel
/// shows in the filtered value.
fn texel(v: [u32; 3]) -> u32 {
    let mut x = v[0].wrapping_mul(0x8da6_b343)
        ^ v[1].wrapping_mul(0xd816_3841)
        ^ v[2].wrapping_mul(0xcb1a_b31f);
    x ^= x >> 15;
    x = x.wrapping_mul(0x2c1b_3c6d);
    x ^ (x >> 12)
}

#[test]
fn blocked_trilinear_lookups_equal_a_dense_grid() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 48;
        let mut v = Voxelizer::new(gpu).unwrap();
        let cells = v
            .cells(&m.positions, &m.triangles, VoxelGrid::cells(r).unwrap())
            .unwrap()
            .read()
            .unwrap();
        let blocked = BlockedPerfectHash::build(&cells, r, texel, None).unwrap();
        // Every block size was built and the smallest kept.
        assert_eq!(blocked.choices.len(), 4);
        let best = blocked.choices.iter().map(|c| c.bytes).min().unwrap();
        assert_eq!(blocked.bytes(), best);
        for c in &blocked.choices {
            assert_eq!(c.blocks, block_keys(&cells, c.block).len());
        }
        // Points on the surface (their footprint cells are stored).
        let mut g = rng(21);
        let points: Vec<Vec3> = m
            .triangles
            .iter()
            .step_by(3)
            .map(|t| point_on_triangle(&mut g, t.map(|i| m.positions[i as usize])))
            .collect();
        for block in [None, Some(1), Some(2), Some(3), Some(4)] {
            let table = match block {
                None => blocked.clone(),
                Some(b) => BlockedPerfectHash::build(&cells, r, texel, Some(b)).unwrap(),
            };
            let uploaded = table.upload(&kernels).unwrap();
            let on_gpu = table.query_gpu(&uploaded, &points).unwrap();
            for (p, g) in points.iter().zip(&on_gpu) {
                let want = trilinear_cpu(|v| Some(texel(v)), *p, r);
                let cpu = table.trilinear(*p);
                let b = table.layout.block;
                assert!(
                    (cpu - want).abs().max_element() <= TRILINEAR_TOLERANCE,
                    "b={b} {p}: {cpu} vs {want}"
                );
                assert!(
                    (*g - want).abs().max_element() <= TRILINEAR_TOLERANCE,
                    "b={b} {p}: GPU {g} vs {want}"
                );
            }
        }
        assert!(BlockedPerfectHash::build(&cells, r, texel, Some(5)).is_err());
    });
}

/// `PerfectConstruction`: `Cpu` is the CPU reference's table uploaded (the same words), `Gpu`
/// the GPU construction's, both perfect on the keys and read alike through the GLSL include;
/// `Auto` is `Cpu` on a CPU device (lavapipe) and `Gpu` on a GPU.
#[test]
fn each_construction_builds_where_it_says_and_auto_follows_the_device_type() {
    with_gpu(|gpu| {
        let kernels = PerfectKernels::new(gpu).unwrap();
        let u = Universe::new_3d([64; 3], KeyLayout::Morton).unwrap();
        let (keys, _) = random_keys(&u, 3000, 0, 11);
        let payloads = payloads_for(&keys);
        let config = PerfectConfig::default();
        let key_buf = lazysolid_compute::gpu::GpuBuffer::from_slice(gpu, "keys", &keys).unwrap();
        let payload_buf =
            lazysolid_compute::gpu::GpuBuffer::from_slice(gpu, "payloads", &payloads).unwrap();
        let build = |c: PerfectConstruction| {
            c.build(&kernels, u, &key_buf, &payload_buf, keys.len(), config)
                .unwrap()
        };
        let cpu = build(PerfectConstruction::Cpu);
        let reference = build_perfect_cpu(u, &keys, &payloads, config).unwrap();
        let cpu_host = cpu.to_host().unwrap();
        assert_eq!(cpu_host.offsets, reference.offsets);
        assert_eq!(cpu_host.data, reference.data);
        let on_gpu = build(PerfectConstruction::Gpu);
        let direct = PerfectBuilder::new(&kernels)
            .build_from_slices(u, &keys, &payloads, config)
            .unwrap()
            .to_host()
            .unwrap();
        let gpu_host = on_gpu.to_host().unwrap();
        assert_eq!(gpu_host.offsets, direct.offsets);
        assert_eq!(gpu_host.data, direct.data);
        for (table, what) in [(&cpu, "cpu"), (&on_gpu, "gpu")] {
            check_table(&table.to_host().unwrap(), &keys, &payloads, &[], what);
            assert_eq!(table.query(&keys).unwrap(), payloads, "{what}");
        }
        let expected = if gpu.info().device_type == "cpu" {
            PerfectConstruction::Cpu
        } else {
            PerfectConstruction::Gpu
        };
        assert_eq!(PerfectConstruction::Auto.resolve(gpu), expected);
        assert_eq!(
            PerfectConstruction::Gpu.resolve(gpu),
            PerfectConstruction::Gpu
        );
        assert_eq!(
            PerfectConstruction::Cpu.resolve(gpu),
            PerfectConstruction::Cpu
        );
    });
}
