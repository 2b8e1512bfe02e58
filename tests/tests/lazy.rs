//! Lazy solid synthesis: the dependency sets and the sparse synthesizer against the full-volume
//! synthesizer (bit for bit on every requested voxel, for scattered voxels, a sphere's surface
//! voxels, a planar slab, and a union requested in two batches in either order), and matter in
//! a store growing by a new surface.

use glam::{DVec3, Vec3, Vec4};
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::{morton_decode, morton_encode};
use lazysolid_compute::store::tiletree;
use lazysolid_compute::store::{
    unpack_rgba8, ColourSource, Filter, HashStore, OctreeConfig, OctreeStore, PerfectStore,
    SparseStore, StoreKernels, TileTree, TileTreeConfig,
};
use lazysolid_compute::voxel::{difference_cpu, union_cpu, VoxelKeys, Voxelizer};
use lazysolid_renderer::fracture::{cut_pieces, fracture, random_sites, Fragment, Plane};
use lazysolid_synth::solid::lazy::{
    dependencies_cpu, lazy_key, lazy_position, order_key, stage_range, GpuLazySolid, LazySolidCpu,
    MatterColours, MatterError, MatterSpec, MatterVoxels, MemoryPolicy, StageRanges, StoredMatter,
    LAZY_MARGIN, MAX_LAZY_COORD,
};
use lazysolid_synth::solid::{
    analyze_solid, balance_usage, candidates_cpu, default_solid_jitter, default_solid_passes,
    level_schedules, synthesize_solid_cpu, CandidateParams, GpuSolidSynthesizer, LevelSchedule,
    SolidAnalysis, SolidCandidates, SolidExemplars, SolidRelief, SolidSynthesis, VolumeBox,
    DEFAULT_BALANCE, DEFAULT_SOLID_PARALLEL_LEVELS,
};
use lazysolid_synth::{SynthError, SynthParams};
use lazysolid_tests::{exemplar_crop, rng, unit_mesh, with_gpu};
use rand::Rng;
use std::collections::BTreeSet;
use std::sync::{Arc, Mutex, OnceLock};

type Case = (SolidExemplars, SolidAnalysis, SolidCandidates, SynthParams);

/// A 16² leather crop in every role, the solid defaults (the usage balance included), seed 5.
fn case() -> &'static Case {
    static CELL: OnceLock<Case> = OnceLock::new();
    CELL.get_or_init(|| {
        let exemplars = SolidExemplars::new(
            exemplar_crop("leather.pat", 8, 8, 16, 16),
            [None, None, None],
        )
        .unwrap();
        let analysis = analyze_solid(&exemplars);
        let mut candidates = candidates_cpu(&analysis, &CandidateParams::default()).unwrap();
        // With the default usage balance, as scenes synthesize: its penalties must reach
        // every synthesizer alike.
        balance_usage(&analysis, &mut candidates, DEFAULT_BALANCE, &mut |_| {}).unwrap();
        let levels = analysis.levels.len() as u32;
        let params = SynthParams::new(
            levels,
            5,
            &default_solid_passes(levels),
            &default_solid_jitter(levels),
        )
        .unwrap()
        .with_parallel_levels(DEFAULT_SOLID_PARALLEL_LEVELS)
        .unwrap();
        (exemplars, analysis, candidates, params)
    })
}

/// The parameters of [`case`] with the finest level's correction in either order: the default
/// first, then the other one (ordered subpasses or one parallel pass).
fn orders() -> [&'static SynthParams; 2] {
    static OTHER: OnceLock<SynthParams> = OnceLock::new();
    let default = &case().3;
    let other = OTHER.get_or_init(|| {
        let flipped = if default.parallel_levels > 0 { 0 } else { 1 };
        default.clone().with_parallel_levels(flipped).unwrap()
    });
    [default, other]
}

/// The resolution of the GPU state: the texture `[0, 16)³` holds [`BOX`].
const RESOLUTION: u32 = 16;

/// The box every request set lies in.
const BOX: VolumeBox = VolumeBox {
    origin: [2, 0, 1],
    size: [14, 13, 12],
};

/// The full volume over [`BOX`] with `params` (one of [`orders`]): the oracle.
fn full(params: &SynthParams) -> &'static SolidSynthesis {
    static CELLS: [OnceLock<SolidSynthesis>; 2] = [OnceLock::new(), OnceLock::new()];
    let i = orders()
        .iter()
        .position(|o| *o == params)
        .expect("one of the orders");
    CELLS[i].get_or_init(|| {
        let (_, analysis, candidates, _) = case();
        synthesize_solid_cpu(analysis, candidates, params, BOX).unwrap()
    })
}

fn oracle(params: &SynthParams, p: [i32; 3]) -> [u32; 3] {
    let f = full(params);
    f.window_triples()[f.window.index(p)]
}

fn scattered() -> Vec<[i32; 3]> {
    let mut r = rng(41);
    (0..60)
        .map(|_| std::array::from_fn(|a| BOX.origin[a] + r.random_range(0..BOX.size[a] as i32)))
        .collect()
}

/// The voxels a sphere of radius 4.5 centred in the box passes through.
fn sphere() -> Vec<[i32; 3]> {
    let c = [9.0f32, 6.5, 7.0];
    (0..BOX.voxels())
        .map(|i| BOX.position(i))
        .filter(|p| {
            let d: f32 = (0..3)
                .map(|a| (p[a] as f32 + 0.5 - c[a]).powi(2))
                .sum::<f32>()
                .sqrt();
            (d - 4.5).abs() < 0.87
        })
        .collect()
}

/// A slab one voxel thick across the box.
fn slab() -> Vec<[i32; 3]> {
    (0..BOX.voxels())
        .map(|i| BOX.position(i))
        .filter(|p| p[2] == 2)
        .collect()
}

fn check(params: &SynthParams, name: &str, got: &[[u32; 3]], requested: &[[i32; 3]]) {
    assert_eq!(got.len(), requested.len());
    let differ: Vec<_> = requested
        .iter()
        .zip(got)
        .filter(|(&p, &t)| oracle(params, p) != t)
        .collect();
    assert!(
        differ.is_empty(),
        "{name} (parallel levels {}): {} of {} voxels differ, first {:?}",
        params.parallel_levels,
        differ.len(),
        requested.len(),
        differ[0]
    );
}

#[test]
fn lazy_equals_the_full_volume_on_every_request_set() {
    let (_, analysis, candidates, _) = case();
    let sets = [
        ("scattered", scattered()),
        ("sphere", sphere()),
        ("slab", slab()),
    ];
    for (params, (name, set)) in orders()
        .into_iter()
        .flat_map(|p| sets.iter().map(move |s| (p, s)))
    {
        let mut lazy = LazySolidCpu::new();
        let got = lazy.request(analysis, candidates, params, set).unwrap();
        check(params, name, &got, set);
        // Far less than the full volume's work at the finest level.
        let finest = *lazy.computed().last().unwrap();
        let box_versions =
            BOX.voxels() as u64 * (1 + params.passes.last().copied().unwrap() as u64);
        println!(
            "{name}: {} voxels, finest versions {finest} (box {box_versions}), state {} bytes",
            set.len(),
            lazy.bytes()
        );
    }
    assert!(sphere().len() > 200 && slab().len() == 14 * 13);
}

#[test]
fn two_batches_equal_one_request_of_their_union_in_either_order() {
    let (_, analysis, candidates, _) = case();
    let a = scattered();
    let b = slab();
    let union: Vec<[i32; 3]> = a.iter().chain(&b).copied().collect();
    for params in orders() {
        let mut once = LazySolidCpu::new();
        check(
            params,
            "union",
            &once.request(analysis, candidates, params, &union).unwrap(),
            &union,
        );
        for (first, second) in [(&a, &b), (&b, &a)] {
            let mut lazy = LazySolidCpu::new();
            let got1 = lazy.request(analysis, candidates, params, first).unwrap();
            let after_first = lazy.computed().to_vec();
            let got2 = lazy.request(analysis, candidates, params, second).unwrap();
            check(params, "first batch", &got1, first);
            check(params, "second batch", &got2, second);
            // Nothing computed twice: the two batches together did exactly the union's work.
            assert_eq!(lazy.computed(), once.computed());
            assert_eq!(lazy.bytes(), once.bytes());
            assert!(after_first.iter().sum::<u64>() < once.computed().iter().sum::<u64>());
            // A repeated request computes nothing.
            lazy.request(analysis, candidates, params, second).unwrap();
            assert_eq!(lazy.computed(), once.computed());
        }
    }
}

#[test]
fn dependency_sets_cover_only_what_is_needed() {
    for params in orders() {
        assert_eq!(
            *params.passes.last().unwrap(),
            1,
            "one pass at the finest level"
        );
        let schedules = level_schedules(params);
        let finest_parallel = schedules.last().unwrap().parallel;
        // Per level the voxels needed, and at the finest level those needed after its pass
        // (corrected).
        let sizes = |p: [i32; 3]| -> (Vec<usize>, usize) {
            let deps = dependencies_cpu(&[lazy_key(p)], &schedules, &|_, _| 0);
            let finest = deps.levels.last().unwrap();
            let set: BTreeSet<u64> = finest.keys.iter().copied().collect();
            assert!(set.contains(&lazy_key(p)));
            let corrected = finest.need.iter().filter(|&&n| n > 0).count();
            (deps.levels.iter().map(|d| d.len()).collect(), corrected)
        };
        let (first, first_corrected) = sizes([0, 0, 0]);
        let (last, last_corrected) = sizes([4, 2, -1]);
        if finest_parallel {
            // One parallel pass: the voxel alone is corrected, from its 18 plane neighbours
            // as upsampled, whatever its class.
            assert_eq!(
                (*first.last().unwrap(), first_corrected),
                (19, 1),
                "{first:?}"
            );
            assert_eq!((*last.last().unwrap(), last_corrected), (19, 1), "{last:?}");
        } else {
            // Class [0, 0, 0] is corrected first: it reads its 18 plane neighbours as
            // upsampled.
            assert_eq!(*first.last().unwrap(), 19, "{first:?}");
            assert_eq!(first_corrected, 1);
            // Class [0, 0, 1] is corrected last: its neighbours are corrected before it, and
            // theirs.
            assert!(*last.last().unwrap() > 19 * 3, "{last:?}");
            assert!(last_corrected > 19, "{last_corrected}");
        }
        // Every level needs the parents of the next one.
        for s in [first, last] {
            assert!(s.iter().all(|&n| n > 0), "{s:?}");
        }
    }
}

/// The correction's stage stretches on the device equal their CPU reference, for ordered and
/// parallel levels, with idle voxels, empty classes, stages past the key's 63 and stretches
/// past one workgroup count's 65,535; each stretch holds exactly the voxels with work of the
/// stage's class needed at that stage or later (every stage up to 63).
#[test]
fn stage_ranges_equal_the_reference_and_hold_each_stage_voxels() {
    with_gpu(|gpu| {
        let ranges = StageRanges::new(gpu).unwrap();
        let mut r = rng(41);
        let schedules = [
            (
                LevelSchedule {
                    passes: 2,
                    parallel: false,
                },
                3000,
                256,
            ),
            (
                LevelSchedule {
                    passes: 3,
                    parallel: true,
                },
                2000,
                256,
            ),
            (
                LevelSchedule {
                    passes: 9,
                    parallel: false,
                },
                500,
                64,
            ),
            (
                LevelSchedule {
                    passes: 1,
                    parallel: false,
                },
                40,
                256,
            ),
            // 65,536 + 1 workgroups of one invocation: the counts fold into y.
            (
                LevelSchedule {
                    passes: 1,
                    parallel: true,
                },
                65_537,
                1,
            ),
        ];
        for (schedule, n, width) in schedules {
            let stages = schedule.final_stage();
            // Classes 5 and 6 stay empty on the ordered levels.
            let voxels: Vec<(bool, u32, u32)> = (0..n)
                .map(|_| {
                    let class = if schedule.parallel {
                        0
                    } else {
                        [0, 1, 2, 3, 4, 7][r.random_range(0..6)]
                    };
                    (r.random_bool(0.2), class, r.random_range(0..=stages))
                })
                .collect();
            let mut keys: Vec<u32> = voxels
                .iter()
                .map(|&(idle, c, s)| order_key(idle, c, s))
                .collect();
            keys.sort_unstable();
            let got = ranges.run(gpu, &keys, schedule, width).unwrap();
            assert_eq!(got.len() as u32, stages);
            for (i, g) in got.iter().enumerate() {
                let stage = i as u32 + 1;
                let (first, len) = stage_range(&keys, schedule, stage);
                assert_eq!([g[3], g[4]], [first, len], "{schedule:?} stage {stage}");
                let blocks = len.div_ceil(width);
                let x = blocks.min(65_535);
                let y = if x == 0 { 1 } else { blocks.div_ceil(x) };
                assert_eq!([g[0], g[1], g[2]], [x, y, 1], "{schedule:?} stage {stage}");
                assert!(u64::from(x) * u64::from(y) * u64::from(width) >= u64::from(len));
                let class = if schedule.parallel {
                    0
                } else {
                    (stage - 1) % 8
                };
                let expected = voxels
                    .iter()
                    .filter(|&&(idle, c, s)| !idle && c == class && s >= stage)
                    .count();
                if stage <= 63 {
                    assert_eq!(len as usize, expected, "{schedule:?} stage {stage}");
                } else {
                    assert!(len as usize >= expected, "{schedule:?} stage {stage}");
                }
            }
        }
    });
}

#[test]
fn requests_outside_the_key_range_are_refused() {
    let (_, analysis, candidates, params) = case();
    let mut lazy = LazySolidCpu::new();
    let err = lazy
        .request(analysis, candidates, params, &[[0, MAX_LAZY_COORD + 1, 0]])
        .unwrap_err();
    assert!(
        matches!(
            err,
            SynthError::Parameter {
                name: "requested voxel y",
                ..
            }
        ),
        "{err}"
    );
    let short = SynthParams::new(2, 0, &[1], &[0.5]).unwrap();
    assert!(lazy
        .request(analysis, candidates, &short, &[[0, 0, 0]])
        .is_err());
}

#[test]
fn gpu_lazy_equals_the_full_volume_and_the_cpu_reference() {
    let (_, analysis, candidates, _) = case();
    let sets = [
        ("scattered", scattered()),
        ("sphere", sphere()),
        ("slab", slab()),
    ];
    with_gpu(|gpu| {
        for params in orders() {
            for (name, set) in &sets {
                let mut lazy =
                    GpuLazySolid::new(gpu, &case().0, analysis, candidates, params, RESOLUTION)
                        .unwrap();
                let (got, report) = lazy.request(set).unwrap();
                check(params, name, &got, set);
                // The dependency walk on the device equals the reference.
                let mut fresh =
                    GpuLazySolid::new(gpu, &case().0, analysis, candidates, params, RESOLUTION)
                        .unwrap();
                assert_eq!(
                    fresh.dependencies(set).unwrap(),
                    dependencies_cpu(
                        &set.iter().map(|&p| lazy_key(p)).collect::<Vec<_>>(),
                        &level_schedules(params),
                        &|_, _| 0
                    ),
                    "{name}: dependency sets"
                );
                let mut cpu = LazySolidCpu::new();
                cpu.request(analysis, candidates, params, set).unwrap();
                assert_eq!(
                    report.computed,
                    cpu.computed(),
                    "{name}: versions computed per level"
                );
            }
            // Two batches in either order: the same triples, and together exactly the union's work.
            let (a, b) = (scattered(), slab());
            let union: Vec<[i32; 3]> = a.iter().chain(&b).copied().collect();
            let mut once = LazySolidCpu::new();
            once.request(analysis, candidates, params, &union).unwrap();
            for (first, second) in [(&a, &b), (&b, &a)] {
                let mut lazy =
                    GpuLazySolid::new(gpu, &case().0, analysis, candidates, params, RESOLUTION)
                        .unwrap();
                let (got1, r1) = lazy.request(first).unwrap();
                let (got2, r2) = lazy.request(second).unwrap();
                check(params, "first batch", &got1, first);
                check(params, "second batch", &got2, second);
                let total: Vec<u64> = r1
                    .computed
                    .iter()
                    .zip(&r2.computed)
                    .map(|(x, y)| x + y)
                    .collect();
                assert_eq!(total, once.computed());
                let (_, r3) = lazy.request(second).unwrap();
                assert!(
                    r3.computed.iter().all(|&c| c == 0),
                    "a repeated request computes nothing"
                );
                assert!(lazy.bytes() > 0);
            }
        }
        let params = &case().3;
        // Outside the texture: refused with the limit.
        let mut lazy =
            GpuLazySolid::new(gpu, &case().0, analysis, candidates, params, RESOLUTION).unwrap();
        let err = lazy.request(&[[0, 16, 0]]).unwrap_err();
        assert!(err.to_string().contains("0..16"), "{err}");
    });
}

#[test]
fn every_memory_policy_returns_the_full_volume_and_recomputes_what_it_dropped() {
    let (exemplars, analysis, candidates, _) = case();
    let (sphere, scattered) = (sphere(), scattered());
    with_gpu(|gpu| {
        // The default order only: the policies act on levels, whatever their schedule.
        for params in [&case().3] {
            let fresh = || {
                GpuLazySolid::new(gpu, exemplars, analysis, candidates, params, RESOLUTION).unwrap()
            };
            // The reference: every version kept, one chunk.
            let mut whole = fresh();
            whole.set_policy(MemoryPolicy::Keep);
            let (_, once) = whole.request(&sphere).unwrap();
            assert_eq!(once.chunks, 1);
            // The levels' bytes as a budget weighs them (fitted to their voxels), from a
            // budget that keeps everything.
            let mut fitted = fresh();
            fitted.set_policy(MemoryPolicy::Budget(u64::MAX));
            fitted.request(&sphere).unwrap();
            assert_eq!(fitted.stored(), whole.stored());
            let level_bytes = fitted.level_bytes();
            let finest = level_bytes.len() - 1;
            // A budget that holds every level but the finest, which a budget weighs last, and
            // one that holds the three coarsest levels and half the fourth's bytes.
            let but_finest = MemoryPolicy::Budget(level_bytes[..finest].iter().sum());
            let part =
                MemoryPolicy::Budget(level_bytes[..3].iter().sum::<u64>() + level_bytes[3] / 2);
            // Chunks of a third and of half the sphere's 460 voxels: every policy acts between
            // chunks, and more chunks would only repeat those steps.
            for (policy, chunk) in [(MemoryPolicy::Keep, 160), (but_finest, 160), (part, 230)] {
                let what = format!("{policy:?}, chunks of {chunk}");
                let mut lazy = fresh();
                lazy.set_policy(policy);
                lazy.set_chunk_voxels(chunk);
                let (got, r) = lazy.request(&sphere).unwrap();
                check(params, &what, &got, &sphere);
                assert_eq!(r.chunks as usize, sphere.len().div_ceil(chunk), "{what}");
                let stored = lazy.stored();
                match policy {
                    MemoryPolicy::Keep => {
                        // Nothing computed twice across chunks, and the same voxels held.
                        assert_eq!(r.computed, once.computed, "{what}");
                        assert_eq!(stored, whole.stored(), "{what}");
                    }
                    MemoryPolicy::Budget(budget) => {
                        assert!(r.dropped_levels > 0, "{what}");
                        let kept = if policy == part { 3 } else { finest };
                        // The kept levels hold what one request holds, in fitted buffers; the
                        // level past the budget the first of its voxels in key order (half
                        // its bytes hold fewer than half its voxels: the table's cells and
                        // the rounding of its buffers), and the rest nothing.
                        assert_eq!(stored[..kept], whole.stored()[..kept], "{what}");
                        if policy == part {
                            let all = whole.stored()[3];
                            assert!(
                                stored[3] > all / 4 && stored[3] < all / 2,
                                "{what}: {stored:?}"
                            );
                            // The first voxels in the order of the table's keys (Morton
                            // codes of the position plus the margin).
                            let table_order = |mut keys: Vec<u64>| {
                                keys.sort_by_key(|&k| {
                                    let p = lazy_position(k).map(|c| (c + LAZY_MARGIN) as u32);
                                    morton_encode(p, 3)
                                });
                                keys
                            };
                            let kept = table_order(lazy.stored_keys(3).unwrap());
                            let first = table_order(fitted.stored_keys(3).unwrap());
                            assert_eq!(kept, first[..kept.len()], "{what}: a region");
                        }
                        let emptied = if policy == part { 4 } else { finest };
                        assert!(
                            stored[emptied..].iter().all(|&n| n == 0),
                            "{what}: {stored:?}"
                        );
                        // The levels holding voxels, within the budget (an emptied level
                        // keeps its first small buffers).
                        let held: u64 = (lazy.level_bytes().iter().zip(&stored))
                            .filter(|(_, &n)| n > 0)
                            .map(|(b, _)| b)
                            .sum();
                        assert!(held <= budget, "{what}: {held} bytes held");
                        assert!(r.peak_state_bytes > held, "{what}");
                    }
                }
                // A later request after eviction: the same triples, recomputed where dropped.
                let (again, r2) = lazy.request(&sphere).unwrap();
                check(params, &what, &again, &sphere);
                let recomputed: u64 = r2.computed.iter().sum();
                assert_eq!(
                    recomputed == 0,
                    policy == MemoryPolicy::Keep,
                    "{what}: {recomputed} versions recomputed"
                );
                let (other, _) = lazy.request(&scattered).unwrap();
                check(params, &what, &other, &scattered);
            }
        }
    });
}

/// The voxels of the cap faces of `pieces` at resolution `r` (what a cut or a fracture asks
/// the matter for), as positions.
fn cap_voxels(v: &mut Voxelizer, pieces: &[Fragment], r: u32) -> Vec<[i32; 3]> {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for p in pieces {
        let base = positions.len() as u32;
        positions.extend_from_slice(&p.positions);
        triangles.extend(p.triangles_of(true).map(|t| t.map(|i| i + base)));
    }
    voxel_positions(&v.surface(&positions, &triangles, r).unwrap())
}

fn voxel_positions(keys: &VoxelKeys) -> Vec<[i32; 3]> {
    let keys = keys.read().unwrap();
    keys.iter()
        .map(|&k| morton_decode(k, 3).map(|c| c as i32))
        .collect()
}

/// The dependency walk on the device equals the host reference on the requests a scene
/// makes of a state that already holds a surface: the caps of a plane cut, the caps of a
/// Voronoi fracture and the surface again, with every level kept and after the budget kept
/// part of the second finest level and none of the finest. The walk runs in one submission
/// once its buffers are large enough, and again, equal, when a set outgrows them.
#[test]
fn device_walk_equals_the_reference_for_caps_from_a_held_surface_and_after_eviction() {
    let (exemplars, analysis, candidates, params) = case();
    let m = unit_mesh("bunny00.off");
    let r = RESOLUTION;
    let schedules = level_schedules(params);
    with_gpu(|gpu| {
        let mut v = Voxelizer::new(gpu).unwrap();
        let surface = voxel_positions(&v.surface(&m.positions, &m.triangles, r).unwrap());
        let b = m.bounds();
        let centre = ((b.min + b.max) * 0.5).as_dvec3();
        let plane = Plane::through(centre, DVec3::new(1.0, 1.0, 0.4));
        let (halves, _) = cut_pieces(vec![Fragment::whole(&m)], plane, &m.source).unwrap();
        let cut = cap_voxels(&mut v, &halves[..1], r);
        let broken = fracture(&m, &random_sites(&m, 4, 3).unwrap()).unwrap();
        let pieces = cap_voxels(&mut v, &broken, r);
        assert!(!cut.is_empty() && pieces.len() > cut.len());
        let mut cpu = LazySolidCpu::new();
        cpu.request(analysis, candidates, params, &surface).unwrap();
        let mut lazy = GpuLazySolid::new(gpu, exemplars, analysis, candidates, params, r).unwrap();
        lazy.set_policy(MemoryPolicy::Budget(u64::MAX));
        lazy.request(&surface).unwrap();
        let fitted = lazy.level_bytes();
        let n = fitted.len();
        let all = lazy.stored();
        for evicted in [false, true] {
            if evicted {
                // Half the second finest level's bytes: it keeps part of its voxels and the
                // finest none. The budget applies after the next chunk, an empty request's.
                let budget = fitted[..n - 2].iter().sum::<u64>() + fitted[n - 2] / 2;
                lazy.set_policy(MemoryPolicy::Budget(budget));
                lazy.request(&[]).unwrap();
            }
            let held = lazy.stored();
            assert_eq!(held[..n - 2], all[..n - 2]);
            if evicted {
                assert!(held[n - 2] > 0 && held[n - 2] < all[n - 2] && held[n - 1] == 0);
            } else {
                assert_eq!(held, all);
            }
            let part: BTreeSet<u64> = lazy.stored_keys(n - 2).unwrap().into_iter().collect();
            let known = |l: usize, k: u64| {
                let kept = !evicted || l < n - 2 || (l == n - 2 && part.contains(&k));
                if kept {
                    cpu.versions(l, k)
                } else {
                    0
                }
            };
            for (name, set) in [
                ("the plane cut's cap", &cut),
                ("the fracture's caps", &pieces),
                ("the surface again", &surface),
            ] {
                let keys: Vec<u64> = set.iter().map(|&p| lazy_key(p)).collect();
                let want = dependencies_cpu(&keys, &schedules, &known);
                assert_eq!(
                    lazy.dependencies(set).unwrap(),
                    want,
                    "{name}, levels emptied: {evicted}"
                );
                // Taught by the first walk, the second runs in one submission, waited for
                // once, whatever the number of levels and stages (besides the staging copies
                // of uploads and read-backs where memory is device-local, as on a discrete
                // GPU).
                let (before, staged) = (gpu.submissions(), gpu.staging_copies());
                assert_eq!(lazy.dependencies(set).unwrap(), want, "{name}, again");
                let staged = gpu.staging_copies() - staged;
                assert_eq!(gpu.submissions().since(before).waits - staged, 1, "{name}");
                // From buffers of one entry, the walk overflows, runs again with what the
                // counters demanded, and still equals the reference.
                lazy.start_walk_small();
                let before = gpu.submissions();
                assert_eq!(lazy.dependencies(set).unwrap(), want, "{name}, retried");
                let waits = gpu.submissions().since(before).waits;
                // The walk stops at what is held: the surface again asks for no new version
                // while its levels are kept (its sets are the request), and the caps do.
                let work = want.new_versions(&schedules, &known);
                assert_eq!(work == 0, !evicted && set == &surface, "{name}: {work}");
                assert!(
                    work == 0 || waits > 1,
                    "{name}: the small buffers overflowed no set"
                );
            }
        }
    });
}

/// A chunk of a request waits on the host a fixed four times (the dependency walk, the
/// lookups and inserts of every level, the synthesis of every level, the colours), whatever
/// the number of levels and stages; the hash tables made or grown, and the walks run again
/// because a set outgrew its buffers, add to it, and the report counts both. The requested
/// keys of `colours` stay on the device (they are never read back: a read would not wait on
/// lavapipe, whose memory is mapped, so the count of waits cannot see it, but `colours` holds
/// no host copy to convert).
#[test]
fn a_request_waits_on_the_host_a_fixed_few_times_per_chunk() {
    let (exemplars, analysis, candidates, params) = case();
    let m = unit_mesh("bunny00.off");
    let r = RESOLUTION;
    let stages: u32 = level_schedules(params)
        .iter()
        .map(LevelSchedule::final_stage)
        .sum();
    with_gpu(|gpu| {
        let mut v = Voxelizer::new(gpu).unwrap();
        let keys = v.surface(&m.positions, &m.triangles, r).unwrap();
        let mut lazy = GpuLazySolid::new(gpu, exemplars, analysis, candidates, params, r).unwrap();
        lazy.set_chunk_voxels(keys.len().div_ceil(4));
        // Work submissions: the staging copies of read-backs (device-local memory, as on a
        // discrete GPU; none on lavapipe's mapped heap) are counted apart.
        let work_waits = |f: &mut dyn FnMut()| {
            let (before, staged) = (gpu.submissions(), gpu.staging_copies());
            f();
            gpu.submissions().since(before).waits - (gpu.staging_copies() - staged)
        };
        let mut report = None;
        let waits = work_waits(&mut || report = Some(lazy.colours(&keys).unwrap().1));
        let report = report.unwrap();
        assert_eq!(report.chunks, 4);
        assert!(report.waits >= waits);
        let retries = u64::from(report.walks - report.chunks);
        // A table made or grown waits once (made) or a few times (rebuilt from its entries).
        let growth = 4 * u64::from(report.table_growths);
        assert!(
            waits <= 4 * u64::from(report.chunks) + retries + growth,
            "{waits} waits in {} chunks, {retries} walks again, {} tables made or grown",
            report.chunks,
            report.table_growths
        );
        // The same voxels again need nothing new: four waits a chunk, far fewer than the
        // levels' {stages} stages.
        let mut again = None;
        let waits = work_waits(&mut || again = Some(lazy.colours(&keys).unwrap().1));
        let again = again.unwrap();
        assert_eq!((again.walks, again.table_growths), (4, 0));
        assert_eq!(waits, 4 * 4);
        assert!(waits / 4 < u64::from(stages));
    });
}

/// The RGBA8 texel of every voxel of the full `[0, R)³` volume of [`case`], synthesized on
/// the GPU in one box, with its CPU texel rule (`voxel_texel`, the relief code in alpha when
/// `relief` is given): what every lazily filled store must hold.
fn full_cube_colours(
    gpu: &lazysolid_compute::gpu::Gpu,
    relief: Option<&SolidRelief>,
) -> impl Fn([u32; 3]) -> u32 {
    let (exemplars, analysis, candidates, params) = case();
    let r = RESOLUTION;
    let window = VolumeBox {
        origin: [0; 3],
        size: [r; 3],
    };
    let full = GpuSolidSynthesizer::new(gpu, analysis, candidates)
        .unwrap()
        .synthesize(analysis, candidates, params, window, false, &mut |_| {})
        .unwrap()
        .0;
    let texels = full.texels(exemplars, relief);
    move |p: [u32; 3]| -> u32 { texels[window.index(p.map(|v| v as i32))] }
}

/// Colours of the interpolation voxels of the bunny at 16³ and of its surface voxels (a second,
/// incremental request), synthesized lazily on the GPU, equal the full volume's; the coherent
/// hash, the N³ tree and the perfect hash built from them return those colours at every voxel
/// centre, and the TileTree's tiles hold them at every texel.
#[test]
fn stores_filled_by_lazy_synthesis_hold_the_full_volume_colours() {
    stores_hold_the_full_volume(false);
}

/// The same with the relief channel in alpha: the lazy kernel's codes (GPU) equal the full
/// volume's by the CPU rule, in every store; and the codes vary (a channel, not a constant).
#[test]
fn stores_filled_by_lazy_synthesis_hold_the_full_volume_relief() {
    stores_hold_the_full_volume(true);
}

fn stores_hold_the_full_volume(with_relief: bool) {
    let (exemplars, analysis, candidates, params) = case();
    let m = unit_mesh("bunny00.off");
    let r = RESOLUTION;
    let relief = with_relief.then(|| SolidRelief::of(exemplars));
    with_gpu(|gpu| {
        let want = full_cube_colours(gpu, relief.as_ref());
        let codes: BTreeSet<u32> = (0..r * r * r)
            .map(|i| want([i % r, i / r % r, i / (r * r)]) >> 24)
            .collect();
        if with_relief {
            assert!(codes.len() >= 3, "relief codes {codes:?}");
            assert!(
                codes.iter().all(|&c| c >= 2),
                "the octree's tags are reserved"
            );
        } else {
            assert_eq!(codes.into_iter().collect::<Vec<_>>(), [255]);
        }
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let interp = v.interpolation(&m.positions, &m.triangles, r).unwrap();
        let surface = v.surface(&m.positions, &m.triangles, r).unwrap();
        let mut lazy = GpuLazySolid::new(gpu, exemplars, analysis, candidates, params, r).unwrap();
        lazy.set_relief(exemplars, relief.clone()).unwrap();
        let (c_interp, first) = lazy.colours(&interp).unwrap();
        let (c_surface, second) = lazy.colours(&surface).unwrap();
        let total = |r: &lazysolid_synth::solid::lazy::LazyReport| r.computed.iter().sum::<u64>();
        assert!(
            total(&second) < total(&first) / 4,
            "the surface mostly reuses the first request"
        );
        for (keys, c) in [(&interp, &c_interp), (&surface, &c_surface)] {
            let (k, c) = (keys.read().unwrap(), c.read().unwrap());
            let bad = k
                .iter()
                .zip(&c)
                .filter(|(&k, &c)| want(morton_decode(k, 3)) != c)
                .count();
            assert_eq!(
                bad,
                0,
                "{bad} of {} lazily synthesized colours differ",
                k.len()
            );
        }
        let keys = interp.read().unwrap();
        let centres: Vec<Vec3> = keys
            .iter()
            .map(|&k| (glam::UVec3::from(morton_decode(k, 3)).as_vec3() + 0.5) / r as f32)
            .collect();
        let expect: Vec<Vec4> = keys
            .iter()
            .map(|&k| unpack_rgba8(want(morton_decode(k, 3))))
            .collect();
        let source = ColourSource::Buffer {
            keys: &interp,
            colours: &c_interp,
        };
        let check = |name: &str, got: Vec<Vec4>| {
            let bad = got.iter().zip(&expect).filter(|(a, b)| a != b).count();
            assert_eq!(bad, 0, "{name}: {bad} of {} voxels differ", expect.len());
        };
        let hash = HashStore::build(&kernels, r, &interp, &source, Default::default()).unwrap();
        check("hash", hash.lookup(&centres, Filter::Nearest).unwrap());
        let config = OctreeConfig::for_resolution(r).unwrap();
        let (octree, _) = OctreeStore::build(&kernels, r, &interp, &source, config).unwrap();
        check("octree", octree.lookup(&centres, Filter::Nearest).unwrap());
        let perfect =
            PerfectStore::build(&kernels, r, &interp, &source, PerfectAccess::Unconstrained)
                .unwrap();
        check(
            "perfect",
            perfect.lookup(&centres, Filter::Nearest).unwrap(),
        );
        let tiles = ColourSource::Buffer {
            keys: &surface,
            colours: &c_surface,
        };
        let (tree, _) = TileTree::build(
            &kernels,
            &m.positions,
            &m.triangles,
            r,
            &tiles,
            TileTreeConfig::default(),
        )
        .unwrap();
        let reference = ColourSource::Fn(&want);
        let texels = tiletree::fill_cpu(tree.plan(), &reference.to_host().unwrap());
        let map = tree.map_words().unwrap();
        let bad = map.iter().zip(&texels).filter(|(a, b)| a != b).count();
        assert_eq!(bad, 0, "tiletree: {bad} of {} words differ", map.len());
    });
}

/// Matter in a store (`StoredMatter`) grows by a new surface through the store's insert:
/// exactly the new surface's voxels the store lacked are synthesized and inserted, every
/// stored voxel holds the full volume's colour, and growing by the same surface again
/// synthesizes and inserts nothing.
#[test]
fn matter_grows_by_a_new_surface_without_synthesizing_a_voxel_twice() {
    let (exemplars, analysis, candidates, params) = case();
    let m = unit_mesh("bunny00.off");
    let r = RESOLUTION;
    with_gpu(|gpu| {
        let want = full_cube_colours(gpu, None);
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let lazy = GpuLazySolid::new(gpu, exemplars, analysis, candidates, params, r).unwrap();
        let shared = Arc::new(Mutex::new(lazy));
        let (mut matter, built) = StoredMatter::build(
            gpu,
            &mut v,
            MatterSpec {
                colours: MatterColours::Lazy(shared.clone()),
                voxels: MatterVoxels::Surface,
                resolution: r,
            },
            &m.positions,
            &m.triangles,
            |keys, source| HashStore::build(&kernels, r, keys.unwrap(), source, Default::default()),
        )
        .unwrap();
        let outer = v
            .surface(&m.positions, &m.triangles, r)
            .unwrap()
            .read()
            .unwrap();
        assert_eq!(matter.held().unwrap().read().unwrap(), outer);
        assert!(built.unwrap().versions > 0);
        // A cap: the square y = 0.47 over [0.2, 0.8]², as a cut through the bunny gives.
        let cap_positions = [
            Vec3::new(0.2, 0.47, 0.2),
            Vec3::new(0.8, 0.47, 0.2),
            Vec3::new(0.8, 0.47, 0.8),
            Vec3::new(0.2, 0.47, 0.8),
        ];
        let cap_triangles = [[0, 2, 1], [0, 3, 2]];
        let cap = v
            .surface(&cap_positions, &cap_triangles, r)
            .unwrap()
            .read()
            .unwrap();
        let lacking = difference_cpu(&cap, &outer);
        assert!(!lacking.is_empty() && lacking.len() < cap.len());
        let grown = matter.grow(&mut v, &cap_positions, &cap_triangles).unwrap();
        assert_eq!(grown.requested_voxels, cap.len() as u64);
        assert_eq!(grown.new_voxels, lacking.len() as u64);
        assert_eq!(grown.texels_added, lacking.len() as u64);
        assert!(grown.synthesis.is_some_and(|s| s.versions > 0));
        let union = union_cpu(&outer, &cap);
        assert_eq!(matter.held().unwrap().read().unwrap(), union);
        assert_eq!(matter.store().len(), union.len() as u64);
        let centres: Vec<Vec3> = union
            .iter()
            .map(|&k| (glam::UVec3::from(morton_decode(k, 3)).as_vec3() + 0.5) / r as f32)
            .collect();
        let got = matter.store().lookup(&centres, Filter::Nearest).unwrap();
        let bad = union
            .iter()
            .zip(&got)
            .filter(|(&k, c)| unpack_rgba8(want(morton_decode(k, 3))) != **c)
            .count();
        assert_eq!(bad, 0, "{bad} of {} stored voxels differ", union.len());
        let again = matter.grow(&mut v, &cap_positions, &cap_triangles).unwrap();
        assert_eq!((again.new_voxels, again.texels_added), (0, 0));
        assert!(again.synthesis.is_none());
        assert_eq!(matter.state_bytes(), shared.lock().unwrap().bytes());
        let unkeyed = MatterSpec {
            colours: MatterColours::Lazy(shared.clone()),
            voxels: MatterVoxels::Unkeyed,
            resolution: r,
        };
        let refused = StoredMatter::<HashStore>::build(
            gpu,
            &mut v,
            unkeyed,
            &m.positions,
            &m.triangles,
            |_, _| unreachable!("refused before any store is built"),
        );
        assert!(matches!(refused, Err(MatterError::UnkeyedLazy)));
    });
}
