//! The sparse stores on the device against their CPU references: every stored voxel and random
//! points, nearest (exact colours), trilinear (stated tolerance) and MIP lookups, inserts of
//! further voxels, the octree's pool word for word, its growth and in-place updates.

use glam::{Vec3, Vec4};
use lazysolid_compute::hash::perfect::{table_bytes, PerfectAccess};
use lazysolid_compute::hash::{morton_decode, morton_encode, RobinHoodConfig};
use lazysolid_compute::store::*;
use lazysolid_compute::voxel::VoxelGrid;
use lazysolid_compute::voxel::{VoxelKeys, Voxelizer};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::{point_on_triangle, rng, unit_mesh, with_gpu};
use rand::Rng;
use std::collections::HashMap;

/// Trilinear results are sums of 8 weighted colours in f32: 1e-5 covers the different
/// summation orders of GPU and CPU.
const TRILINEAR_TOLERANCE: f32 = 1e-5;

/// Interpolation voxels of the bunny, split into a build half and an insert half.
fn voxel_sets(v: &mut Voxelizer, m: &Mesh, r: u32) -> (Vec<u64>, Vec<u64>, Vec<u64>) {
    let all = v
        .interpolation(&m.positions, &m.triangles, r)
        .unwrap()
        .read()
        .unwrap();
    let first = all.iter().copied().filter(|k| k % 3 != 0).collect();
    let second = all.iter().copied().filter(|k| k % 3 == 0).collect();
    (all, first, second)
}

fn points(m: &Mesh, r: u32, seed: u64) -> Vec<Vec3> {
    let mut g = rng(seed);
    let mut pts: Vec<Vec3> = m
        .triangles
        .iter()
        .step_by(5)
        .map(|t| point_on_triangle(&mut g, t.map(|i| m.positions[i as usize])))
        .collect();
    // Points anywhere (mostly not stored) and outside the cube.
    pts.extend((0..500).map(|_| Vec3::new(g.random(), g.random(), g.random())));
    pts.extend([
        Vec3::splat(-0.3),
        Vec3::splat(1.2),
        Vec3::new(0.5, 2.0, 0.5),
    ]);
    let _ = r;
    pts
}

fn centres(keys: &[u64], r: u32) -> Vec<Vec3> {
    keys.iter()
        .map(|&k| (glam::UVec3::from(morton_decode(k, 3)).as_vec3() + 0.5) / r as f32)
        .collect()
}

fn check_lookups<S: SparseStore>(
    store: &S,
    texel: impl Fn([u32; 3]) -> Option<u32> + Copy,
    stored: &[u64],
    pts: &[Vec3],
) {
    let r = store.resolution();
    let what = store.name();
    // Every stored voxel, at its centre: exact colours.
    let c = centres(stored, r);
    let got = store.lookup(&c, Filter::Nearest).unwrap();
    for (i, (&k, g)) in stored.iter().zip(&got).enumerate() {
        let want = unpack_rgba8(texel(morton_decode(k, 3)).unwrap());
        assert_eq!(*g, want, "{what}: voxel {i} {:?}", morton_decode(k, 3));
    }
    let near = store.lookup(pts, Filter::Nearest).unwrap();
    let tri = store.lookup(pts, Filter::Trilinear).unwrap();
    let mut undefined = 0;
    for (i, &p) in pts.iter().enumerate() {
        let want = unpack_rgba8(nearest_cpu(texel, p, r));
        assert_eq!(near[i], want, "{what}: nearest at {p}");
        undefined += (want.w == 0.0) as usize;
        let want = trilinear_cpu(texel, p, r);
        assert!(
            (tri[i] - want).abs().max_element() <= TRILINEAR_TOLERANCE,
            "{what}: trilinear at {p}: {} vs {want}",
            tri[i]
        );
    }
    assert!(undefined > 0, "{what}: some points must miss");
    assert_eq!(near[pts.len() - 1], Vec4::ZERO);
}

#[test]
fn marble_on_the_gpu_equals_the_cpu() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        for r in [64, 100] {
            let keys = v.surface(&m.positions, &m.triangles, r).unwrap();
            let source = ColourSource::Marble { seed: 9 };
            let store =
                HashStore::build(&kernels, r, &keys, &source, RobinHoodConfig::default()).unwrap();
            let host = keys.read().unwrap();
            let got = store.lookup(&centres(&host, r), Filter::Nearest).unwrap();
            for (k, g) in host.iter().zip(got) {
                let v = morton_decode(*k, 3);
                assert_eq!(g, unpack_rgba8(marble_rgba8(v, r, 9)), "{v:?} R={r}");
            }
        }
    });
}

/// A colour that differs between neighbouring voxels, so a lookup of the wrong voxel shows.
fn voxel_colour(p: [u32; 3]) -> u32 {
    0xff00_0000 | p[0] | (p[1] << 8) | ((p[2] * 7) & 255) << 16
}

/// [`voxel_colour`] of every Morton key of `all`, by voxel position.
fn colour_map(all: &[u64]) -> HashMap<[u32; 3], u32> {
    all.iter()
        .map(|&k| (morton_decode(k, 3), voxel_colour(morton_decode(k, 3))))
        .collect()
}

#[test]
fn hash_store_matches_its_reference_and_grows_by_inserts() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 128;
        let (all, first, second) = voxel_sets(&mut v, &m, r);
        let f = voxel_colour;
        let source = ColourSource::Fn(&f);
        let k1 = VoxelKeys::from_sorted(gpu, "first", &first).unwrap();
        let k2 = VoxelKeys::from_sorted(gpu, "second", &second).unwrap();
        let config = RobinHoodConfig {
            load_factor: 0.95,
            ..Default::default()
        };
        let mut store = HashStore::build(&kernels, r, &k1, &source, config).unwrap();
        assert_eq!(store.len(), first.len() as u64);
        let report = store.insert(&k2, &source).unwrap();
        assert_eq!(report.texels, all.len() as u64);
        assert!(
            !report.reallocations.is_empty(),
            "colours and table must grow"
        );
        let map = colour_map(&all);
        check_lookups(&store, |p| map.get(&p).copied(), &all, &points(&m, r, 3));
        assert!(store.bytes() >= all.len() as u64 * 12);
        // Inserting a stored voxel again is refused and changes nothing.
        let again = VoxelKeys::from_sorted(gpu, "again", &second[..3]).unwrap();
        let e = store.insert(&again, &source);
        assert!(
            matches!(e, Err(StoreError::AlreadyStored { .. })),
            "{:?}",
            e.err()
        );
        assert_eq!(store.len(), all.len() as u64);
    });
}

#[test]
fn perfect_store_matches_its_reference_in_both_layouts_and_grows_by_rebuilds() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 96;
        let (all, first, second) = voxel_sets(&mut v, &m, r);
        let f = voxel_colour;
        let source = ColourSource::Fn(&f);
        let map = colour_map(&all);
        let texel = |p| map.get(&p).copied();
        let pts = points(&m, r, 5);
        let surface = m.triangles.len().div_ceil(5);

        // Unconstrained texel layout: unstored voxels read 0, so the full reference check
        // applies; built on half the voxels, the other half inserted by a rebuild.
        let k1 = VoxelKeys::from_sorted(gpu, "first", &first).unwrap();
        let k2 = VoxelKeys::from_sorted(gpu, "second", &second).unwrap();
        let mut store =
            PerfectStore::build(&kernels, r, &k1, &source, PerfectAccess::Unconstrained).unwrap();
        assert_eq!(store.len(), first.len() as u64);
        let report = store.insert(&k2, &source).unwrap();
        assert_eq!(report.texels, all.len() as u64);
        assert!(
            report.reallocations[0]
                .contains(&format!("perfect hash rebuilt for {} keys", all.len())),
            "{:?}",
            report.reallocations
        );
        check_lookups(&store, texel, &all, &pts);
        let sizes = *store.table().sizes();
        assert_eq!(
            store.bytes(),
            table_bytes(&sizes, PerfectAccess::Unconstrained, 1)
        );
        let again = VoxelKeys::from_sorted(gpu, "again", &second[..3]).unwrap();
        let e = store.insert(&again, &source);
        assert!(
            matches!(e, Err(StoreError::AlreadyStored { .. })),
            "{:?}",
            e.err()
        );
        assert_eq!(store.len(), all.len() as u64);

        // Constrained texel layout (no keys stored): exact at every stored voxel, trilinear
        // within the tolerance at surface points (all 8 corners stored), 4 B per slot + Φ.
        let keys = VoxelKeys::from_sorted(gpu, "all", &all).unwrap();
        let store =
            PerfectStore::build(&kernels, r, &keys, &source, PerfectAccess::Constrained).unwrap();
        let got = store.lookup(&centres(&all, r), Filter::Nearest).unwrap();
        for (&k, g) in all.iter().zip(&got) {
            assert_eq!(*g, unpack_rgba8(f(morton_decode(k, 3))));
        }
        let tri = store.lookup(&pts[..surface], Filter::Trilinear).unwrap();
        for (p, t) in pts[..surface].iter().zip(&tri) {
            let want = trilinear_cpu(texel, *p, r);
            assert!(
                (*t - want).abs().max_element() <= TRILINEAR_TOLERANCE,
                "{p}"
            );
        }
        let sizes = *store.table().sizes();
        assert_eq!(
            store.bytes(),
            table_bytes(&sizes, PerfectAccess::Constrained, 1)
        );
        let bits = (store.bytes() - 4 * sizes.slots() as u64) as f64 * 8.0 / all.len() as f64;
        let want = sizes.bits_per_key(all.len());
        assert!(
            bits >= want && bits <= want + 128.0 / all.len() as f64,
            "offset table {bits} bits per key, sizes say {want}: {:?}",
            store.table().report
        );

        // Blocked layout from the interpolation cells: one block per trilinear lookup, the same
        // filtered colours as the reference, and nearest from the block.
        let cells = v
            .cells(&m.positions, &m.triangles, VoxelGrid::cells(r).unwrap())
            .unwrap();
        let blocked = PerfectStore::build_blocked(&kernels, r, &cells, &source, None).unwrap();
        let b = blocked.block().expect("a block size");
        assert!((1..=4).contains(&b), "{b}");
        let tri = blocked.lookup(&pts[..surface], Filter::Trilinear).unwrap();
        let near = blocked.lookup(&pts[..surface], Filter::Nearest).unwrap();
        for (i, p) in pts[..surface].iter().enumerate() {
            let want = trilinear_cpu(texel, *p, r);
            assert!(
                (tri[i] - want).abs().max_element() <= TRILINEAR_TOLERANCE,
                "blocked b={b} at {p}: {} vs {want}",
                tri[i]
            );
            assert_eq!(near[i], unpack_rgba8(nearest_cpu(texel, *p, r)), "{p}");
        }
        let e = PerfectStore::build_blocked(&kernels, r, &cells, &source, Some(5));
        assert!(e.is_err());
        // The blocked layout grows by cells (tested with device colours below); cells it
        // holds are refused.
        let mut blocked = blocked;
        assert!(matches!(
            blocked.insert(&cells, &source),
            Err(StoreError::AlreadyStored { .. })
        ));
    });
}

#[test]
fn octree_matches_its_reference_word_for_word() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        for (r, levels) in [(128, vec![8, 4, 4]), (100, vec![5, 5, 4]), (64, vec![2; 6])] {
            let (all, first, second) = voxel_sets(&mut v, &m, r);
            let source = ColourSource::Marble { seed: 4 };
            let config = OctreeConfig {
                levels: levels.clone(),
                initial_pool_words: 1024,
            };
            let k1 = VoxelKeys::from_sorted(gpu, "first", &first).unwrap();
            let k2 = VoxelKeys::from_sorted(gpu, "second", &second).unwrap();
            let (mut store, report) =
                OctreeStore::build(&kernels, r, &k1, &source, config.clone()).unwrap();
            assert!(
                !report.reallocations.is_empty(),
                "a 1024-word pool must grow"
            );
            let mut cpu = OctreeCpu::new(&config);
            let colours = |keys: &[u64]| -> Vec<u32> {
                keys.iter()
                    .map(|&k| marble_rgba8(morton_decode(k, 3), r, 4))
                    .collect()
            };
            cpu.insert(&first, &colours(&first));
            assert!(
                store.pool_words().unwrap() == cpu.pool,
                "R={r} {levels:?}: pool after build"
            );
            store.insert(&k2, &source).unwrap();
            cpu.insert(&second, &colours(&second));
            assert!(
                store.pool_words().unwrap() == cpu.pool,
                "R={r} {levels:?}: pool after insert"
            );
            assert_eq!(store.len(), all.len() as u64);
            let pts = points(&m, r, 5);
            check_lookups(&store, |p| cpu.texel(p), &all, &pts);
            for depth in 0..=levels.len() as u32 {
                let got = store.lookup_mip(&pts, depth).unwrap();
                for (p, g) in pts.iter().zip(got) {
                    let want = cpu.mip(nearest_voxel(*p, r), depth as usize);
                    assert_eq!(g, unpack_rgba8(want), "R={r} mip {depth} at {p}");
                }
            }
            // In-place update of stored leaves, then averages again.
            let f = |p: [u32; 3]| 0x8000_0000 | (p[0] * 3 + p[1] + p[2]) & 0xff_ffff;
            store.update(&k2, &ColourSource::Fn(&f)).unwrap();
            let new: Vec<u32> = second.iter().map(|&k| f(morton_decode(k, 3))).collect();
            cpu.update(&second, &new);
            assert!(
                store.pool_words().unwrap() == cpu.pool,
                "R={r}: pool after update"
            );
            // Refusals: stored again, reserved alpha, an update of absent voxels.
            assert!(matches!(
                store.insert(&k2, &source),
                Err(StoreError::AlreadyStored { .. })
            ));
            let clear = |_: [u32; 3]| 0x01ff_ffffu32;
            let outside = VoxelKeys::from_sorted(gpu, "absent", &[u64::from(0u32)]).unwrap();
            if !all.contains(&0) {
                assert!(matches!(
                    store.insert(&outside, &ColourSource::Fn(&clear)),
                    Err(StoreError::ReservedAlpha { alpha: 1, .. })
                ));
                assert!(store.update(&outside, &source).is_err());
            }
            assert!(
                store.pool_words().unwrap() == cpu.pool,
                "R={r}: refusals change nothing"
            );
        }
    });
}

#[test]
fn octree_configurations() {
    assert_eq!(
        OctreeConfig::for_resolution(1024).unwrap().levels,
        [8, 8, 4, 4]
    );
    assert_eq!(OctreeConfig::for_resolution(256).unwrap().levels, [8, 8, 4]);
    assert_eq!(OctreeConfig::for_resolution(128).unwrap().levels, [8, 4, 4]);
    assert_eq!(
        OctreeConfig::for_resolution(2048).unwrap().levels,
        [8, 8, 8, 4]
    );
    assert_eq!(OctreeConfig::for_resolution(100).unwrap().levels, [5, 5, 4]);
    assert!(OctreeConfig::for_resolution(2 * 67).is_err());
    let bad = OctreeConfig {
        levels: vec![8, 8],
        initial_pool_words: 0,
    };
    let e = bad.check(128).unwrap_err().to_string();
    assert!(e.contains("multiply to 64"), "{e}");
}

/// Sizes and build times for docs/stores.md (run with `--ignored --nocapture`).
#[test]
#[ignore]
fn measure_store_sizes() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let res: Vec<u32> = std::env::var("STORE_MEASURE_R")
            .map(|s| s.split(',').map(|x| x.parse().unwrap()).collect())
            .unwrap_or(vec![256]);
        for name in ["bunny00.off", "armadillo.off"] {
            let m = unit_mesh(name);
            for &r in &res {
                let t = std::time::Instant::now();
                let surface = v.surface(&m.positions, &m.triangles, r).unwrap();
                let ts = t.elapsed();
                let t = std::time::Instant::now();
                let interp = v.interpolation(&m.positions, &m.triangles, r).unwrap();
                let ti = t.elapsed();
                println!(
                    "{name} R={r}: surface {} voxels ({ts:.2?}), interpolation {} voxels ({ti:.2?})",
                    surface.len, interp.len
                );
                let source = ColourSource::Marble { seed: 1 };
                for (set, keys) in [("nearest", &surface), ("trilinear", &interp)] {
                    let t = std::time::Instant::now();
                    let h =
                        HashStore::build(&kernels, r, keys, &source, RobinHoodConfig::default())
                            .unwrap();
                    let th = t.elapsed();
                    let t = std::time::Instant::now();
                    let config = OctreeConfig {
                        initial_pool_words: 1 << 20,
                        ..OctreeConfig::for_resolution(r).unwrap()
                    };
                    let (o, _) = OctreeStore::build(&kernels, r, keys, &source, config).unwrap();
                    let to = t.elapsed();
                    println!(
                        "  {set}: hash {} bytes (table {} cells, {th:.2?}); octree {:?} pool {} used words = {} bytes, capacity {} bytes, total {} bytes, nodes {:?} ({to:.2?})",
                        h.bytes(),
                        h.table().table_size(),
                        o.config().levels,
                        o.pool_words().unwrap().len(),
                        4 * o.pool_words().unwrap().len(),
                        4 * o.pool_capacity(),
                        o.bytes(),
                        o.node_counts()
                    );
                }
            }
        }
    });
}

/// Uploads the colours of `keys` as a kernel would leave them: a device buffer parallel to the
/// keys.
fn device_colours(
    gpu: &lazysolid_compute::gpu::Gpu,
    keys: &[u64],
) -> lazysolid_compute::gpu::GpuBuffer<u32> {
    let colours: Vec<u32> = keys
        .iter()
        .map(|&k| voxel_colour(morton_decode(k, 3)))
        .collect();
    lazysolid_compute::gpu::GpuBuffer::from_slice(gpu, "synthesized colours", &colours).unwrap()
}

/// Lookups of a store grown by an insert against the store built from the union: nearest and
/// trilinear results identical at every stored voxel and at the test points.
fn same_lookups<S: SparseStore, T: SparseStore>(grown: &S, union: &T, all: &[u64], pts: &[Vec3]) {
    let r = grown.resolution();
    let what = grown.name();
    for (points, filters) in [
        (centres(all, r), &[Filter::Nearest][..]),
        (pts.to_vec(), &[Filter::Nearest, Filter::Trilinear][..]),
    ] {
        for &filter in filters {
            let a = grown.lookup(&points, filter).unwrap();
            let b = union.lookup(&points, filter).unwrap();
            let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
            assert_eq!(differ, 0, "{what} {filter:?}: {differ} lookups differ");
        }
    }
}

/// Every volume store, built from half of the bunny's interpolation voxels with colours from a
/// device buffer (a subset of the buffer's keys: looked up on the device), then grown by the
/// other half (the buffer's own keys: copied), reads exactly like the store built from all
/// voxels with a CPU function, and like the CPU reference. The blocked perfect hash grows by
/// interpolation cells the same way.
#[test]
fn stores_grown_from_device_colours_equal_stores_built_from_the_union() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 64;
        let (all, first, second) = voxel_sets(&mut v, &m, r);
        let f = voxel_colour;
        let function = ColourSource::Fn(&f);
        let all_keys = VoxelKeys::from_sorted(gpu, "all", &all).unwrap();
        let all_colours = device_colours(gpu, &all);
        let from_all = ColourSource::Buffer {
            keys: &all_keys,
            colours: &all_colours,
        };
        let k1 = VoxelKeys::from_sorted(gpu, "first", &first).unwrap();
        let k2 = VoxelKeys::from_sorted(gpu, "second", &second).unwrap();
        let c2 = device_colours(gpu, &second);
        let own = ColourSource::Buffer {
            keys: &k2,
            colours: &c2,
        };
        // The CPU twin of the device lookup gives every voxel of the subset its colour.
        let host_colours = all_colours.read().unwrap();
        let by_key = colours_by_key_cpu(&first, &all, &host_colours, None);
        assert!(first
            .iter()
            .zip(&by_key)
            .all(|(&k, c)| *c == Some(f(morton_decode(k, 3)))));
        let map = colour_map(&all);
        let texel = |p| map.get(&p).copied();
        let pts = points(&m, r, 21);

        let mut hash = HashStore::build(&kernels, r, &k1, &from_all, Default::default()).unwrap();
        hash.insert(&k2, &own).unwrap();
        let union =
            HashStore::build(&kernels, r, &all_keys, &function, Default::default()).unwrap();
        same_lookups(&hash, &union, &all, &pts);
        check_lookups(&hash, texel, &all, &pts);

        let config = OctreeConfig::for_resolution(r).unwrap();
        let (mut octree, _) =
            OctreeStore::build(&kernels, r, &k1, &from_all, config.clone()).unwrap();
        octree.insert(&k2, &own).unwrap();
        let (union, _) = OctreeStore::build(&kernels, r, &all_keys, &function, config).unwrap();
        same_lookups(&octree, &union, &all, &pts);
        check_lookups(&octree, texel, &all, &pts);

        let access = PerfectAccess::Unconstrained;
        let mut perfect = PerfectStore::build(&kernels, r, &k1, &from_all, access).unwrap();
        let report = perfect.insert(&k2, &own).unwrap();
        assert!(report.reallocations[0].contains("rebuilt"), "{report:?}");
        let union = PerfectStore::build(&kernels, r, &all_keys, &function, access).unwrap();
        same_lookups(&perfect, &union, &all, &pts);
        check_lookups(&perfect, texel, &all, &pts);

        // Blocked layout: cells, whose corners are the interpolation voxels.
        let grid = VoxelGrid::cells(r).unwrap();
        let cells = v
            .cells(&m.positions, &m.triangles, grid)
            .unwrap()
            .read()
            .unwrap();
        let (c1, c2): (Vec<u64>, Vec<u64>) = cells.iter().copied().partition(|&c| c % 4 != 1);
        let c1 = VoxelKeys::from_sorted(gpu, "cells 1", &c1).unwrap();
        let c2 = VoxelKeys::from_sorted(gpu, "cells 2", &c2).unwrap();
        let every = VoxelKeys::from_sorted(gpu, "cells", &cells).unwrap();
        let mut blocked =
            PerfectStore::build_blocked(&kernels, r, &c1, &from_all, Some(2)).unwrap();
        assert_eq!(blocked.insert_unit(), InsertUnit::Cells);
        let report = blocked.insert(&c2, &from_all).unwrap();
        assert!(
            report.reallocations[0].contains("blocked perfect hash (b = 2) rebuilt"),
            "{report:?}"
        );
        let union = PerfectStore::build_blocked(&kernels, r, &every, &function, Some(2)).unwrap();
        let surface = &pts[..m.triangles.len().div_ceil(5)];
        for filter in [Filter::Nearest, Filter::Trilinear] {
            let a = blocked.lookup(surface, filter).unwrap();
            assert_eq!(
                a,
                union.lookup(surface, filter).unwrap(),
                "blocked {filter:?}"
            );
            for (p, got) in surface.iter().zip(&a) {
                let want = match filter {
                    Filter::Nearest => unpack_rgba8(nearest_cpu(texel, *p, r)),
                    Filter::Trilinear => trilinear_cpu(texel, *p, r),
                };
                assert!(
                    (*got - want).abs().max_element() <= TRILINEAR_TOLERANCE,
                    "{p}"
                );
            }
        }
        // Cells stored already are refused, and the store is unchanged.
        assert!(matches!(
            blocked.insert(&c2, &from_all),
            Err(StoreError::AlreadyStored { .. })
        ));
        assert_eq!(
            blocked.lookup(surface, Filter::Trilinear).unwrap(),
            union.lookup(surface, Filter::Trilinear).unwrap()
        );
        // A volume store refuses surface triangles and says what it takes instead.
        let e = hash.insert_surface(&m.positions, &m.triangles, &function);
        assert!(
            matches!(e, Err(StoreError::Unsupported { .. })),
            "{:?}",
            e.err()
        );
        assert_eq!(hash.insert_unit(), InsertUnit::Voxels);
    });
}

/// Device colour sources that lack a voxel, or hold fewer colours than keys, and keys outside
/// the grid (checked on the device) are refused by every store with the store, the voxel and
/// the limit named; a refused insert changes nothing.
#[test]
fn bad_keys_and_device_colours_are_named() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let r = 100;
        let voxels: Vec<[u32; 3]> = (0..40).map(|i| [i, 2 * i % r, (7 * i) % r]).collect();
        let mut keys: Vec<u64> = voxels.iter().map(|&p| morton_encode(p, 3)).collect();
        keys.sort_unstable();
        let k = VoxelKeys::from_sorted(gpu, "keys", &keys).unwrap();
        // The source lacks the smallest key.
        let partial = VoxelKeys::from_sorted(gpu, "partial", &keys[1..]).unwrap();
        let partial_colours = device_colours(gpu, &keys[1..]);
        let lacking = ColourSource::Buffer {
            keys: &partial,
            colours: &partial_colours,
        };
        let short =
            lazysolid_compute::gpu::GpuBuffer::from_slice(gpu, "short", &[0u32; 3]).unwrap();
        let too_few = ColourSource::Buffer {
            keys: &k,
            colours: &short,
        };
        // Keys outside the 100³ grid: x = 100 and y = 127 (inside the Morton cube of 128).
        let mut outside = keys.clone();
        outside.push(morton_encode([100, 0, 0], 3));
        outside.push(morton_encode([3, 127, 0], 3));
        outside.sort_unstable();
        let first_out = key_outside_grid(&outside, r).expect("a key outside");
        let out = VoxelKeys::from_sorted(gpu, "outside", &outside).unwrap();
        let fine = ColourSource::Marble { seed: 1 };
        let missing = |e: Result<(), StoreError>, what: &str| match e {
            Err(StoreError::MissingColour { voxel, count, .. }) => {
                assert_eq!((voxel, count), (morton_decode(keys[0], 3), 1), "{what}")
            }
            e => panic!("{what}: {e:?}"),
        };
        let few = |e: Result<(), StoreError>, what: &str| {
            let e = e.unwrap_err().to_string();
            assert!(e.contains("3 colours for 40 keys"), "{what}: {e}");
        };
        let grid = |e: Result<(), StoreError>, what: &str, limit: u32| match e {
            Err(StoreError::KeyOutsideGrid {
                key, resolution, ..
            }) => assert_eq!((key, resolution), (first_out, limit), "{what}"),
            e => panic!("{what}: {e:?}"),
        };
        let hash = |s: &ColourSource<'_>, k: &VoxelKeys| {
            HashStore::build(&kernels, r, k, s, Default::default()).map(drop)
        };
        missing(hash(&lacking, &k), "hash");
        few(hash(&too_few, &k), "hash");
        grid(hash(&fine, &out), "hash", r);
        let octree = |s: &ColourSource<'_>, k: &VoxelKeys| {
            let config = OctreeConfig::for_resolution(r).unwrap();
            OctreeStore::build(&kernels, r, k, s, config).map(drop)
        };
        missing(octree(&lacking, &k), "octree");
        few(octree(&too_few, &k), "octree");
        grid(octree(&fine, &out), "octree", r);
        let perfect = |s: &ColourSource<'_>, k: &VoxelKeys| {
            PerfectStore::build(&kernels, r, k, s, PerfectAccess::Constrained).map(drop)
        };
        missing(perfect(&lacking, &k), "perfect");
        few(perfect(&too_few, &k), "perfect");
        grid(perfect(&fine, &out), "perfect", r);
        // The blocked layout checks cells against the shifted grid of R + 1.
        let cells_out =
            VoxelKeys::from_sorted(gpu, "cells", &[morton_encode([101, 0, 0], 3)]).unwrap();
        let e = PerfectStore::build_blocked(&kernels, r, &cells_out, &fine, None).map(drop);
        match e {
            Err(StoreError::KeyOutsideGrid {
                resolution, voxel, ..
            }) => {
                assert_eq!((resolution, voxel), (r + 1, [101, 0, 0]))
            }
            e => panic!("blocked: {e:?}"),
        }
        // An insert with a lacking source changes nothing.
        let mut store = HashStore::build(&kernels, r, &partial, &fine, Default::default()).unwrap();
        let first = VoxelKeys::from_sorted(gpu, "first", &keys[..1]).unwrap();
        missing(store.insert(&first, &lacking).map(drop), "hash insert");
        assert_eq!(store.len(), keys.len() as u64 - 1);
        assert_eq!(
            store
                .lookup(&centres(&keys[..1], r), Filter::Nearest)
                .unwrap(),
            [Vec4::ZERO]
        );
    });
}
