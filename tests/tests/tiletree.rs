//! The TileTree store: the GPU fill equals its CPU reference texel for texel, GPU lookups equal
//! the CPU lookup, lookups match a dense-grid reference of the same colour source (including
//! bilinear footprints that straddle tile borders and points where the face switches), memory
//! accounting, the tile-map image and the errors.

use glam::{Vec3, Vec4};
use lazysolid_compute::store::tiletree::{self, pick_face, Plan, TileTreeHost, LEAF_WORDS};
use lazysolid_compute::store::*;
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::{point_on_triangle, rng, unit_mesh, with_gpu};
use rand::Rng;

/// GPU and CPU bilinear lookups sum four weighted colours in f32 in the same order; 1e-6
/// allows for a different rounding of the weights.
const ROUNDING: f32 = 1e-6;

/// The TileTree of `m` at resolution `r` with the default configuration.
fn build(
    kernels: &std::sync::Arc<StoreKernels>,
    m: &Mesh,
    r: u32,
    source: &ColourSource<'_>,
) -> (TileTree, StoreReport) {
    TileTree::build(
        kernels,
        &m.positions,
        &m.triangles,
        r,
        source,
        TileTreeConfig::default(),
    )
    .unwrap()
}

/// The icosphere shrunk to radius 0.4 around the cube's centre (away from the grid's edge).
fn sphere(subdivisions: u32) -> Mesh {
    let mut m = Mesh::icosphere(subdivisions);
    for p in &mut m.positions {
        *p = Vec3::splat(0.5) + (*p - 0.5) * 0.8;
    }
    m
}

/// Random points on the triangles with their geometric normals (every `step`-th triangle).
fn surface_points(m: &Mesh, step: usize, per: usize, seed: u64) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut g = rng(seed);
    let mut pts = Vec::new();
    let mut nrm = Vec::new();
    for t in m.triangles.iter().step_by(step) {
        let [p0, p1, p2] = t.map(|i| m.positions[i as usize]);
        let n = (p1 - p0).cross(p2 - p0);
        if n.length_squared() == 0.0 {
            continue;
        }
        for _ in 0..per {
            pts.push(point_on_triangle(&mut g, [p0, p1, p2]));
            nrm.push(n.normalize());
        }
    }
    (pts, nrm)
}

fn host<'a>(plan: &'a Plan, map: &'a [u32]) -> TileTreeHost<'a> {
    TileTreeHost {
        resolution: plan.resolution,
        nodes: &plan.nodes,
        root: plan.root,
        leaves: &plan.leaf_records,
        map,
        map_width: plan.stats.map_width,
    }
}

/// Whether the bilinear footprint at `p` reads a border texel of its tile, and the face read.
fn footprint_class(h: &TileTreeHost<'_>, p: Vec3, n: Vec3) -> Option<(bool, u32, u32)> {
    let r = h.resolution as f32;
    let g = p * r;
    let voxel = g.floor().clamp(Vec3::ZERO, Vec3::splat(r - 1.0)).as_uvec3();
    let leaf = tiletree::descend(h, voxel.to_array())?;
    let rec = &h.leaves[LEAF_WORDS * leaf as usize..];
    let origin = [rec[0] & 0xffff, rec[0] >> 16, rec[1] & 0xffff];
    let face = pick_face(rec[1] >> 24, n);
    let rect = rec[3 + 2 * face as usize];
    let first = [rect & 0xff, (rect >> 8) & 0xff];
    let size = [((rect >> 16) & 0xff) + 1, (rect >> 24) + 1];
    let a = face as usize / 2;
    let border = [(a + 1) % 3, (a + 2) % 3]
        .iter()
        .enumerate()
        .any(|(k, &b)| {
            let t = g[b] - (origin[b] + first[k]) as f32 + 0.5;
            t < 1.0 || t >= size[k] as f32
        });
    Some((border, face, leaf))
}

fn linear_colour(k: u32) -> impl Fn([u32; 3]) -> u32 + Sync {
    move |v: [u32; 3]| 0xff00_0000 | (40 + k * v[0]) | (40 + k * v[1]) << 8 | (40 + k * v[2]) << 16
}

#[test]
fn gpu_fill_and_lookups_equal_the_cpu_references() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let source = ColourSource::Marble { seed: 5 };
        for (name, m, r) in [
            ("bunny", unit_mesh("bunny00.off"), 64),
            ("sphere", sphere(3), 128),
        ] {
            let (tree, report) = build(&kernels, &m, r, &source);
            let plan = tree.plan();
            assert_eq!(report.texels, plan.stats.tile_texels);
            let map = tree.map_words().unwrap();
            let want = tiletree::fill_cpu(plan, &source.to_host().unwrap());
            let diff = map.iter().zip(&want).filter(|(a, b)| a != b).count();
            assert_eq!(diff, 0, "{name} R={r}: {diff} tile-map words differ");
            assert!(map.iter().all(|&w| w == 0 || w >> 24 == 255));
            // Lookups: surface points, points off the surface, and points outside the cube.
            let (mut pts, mut nrm) = surface_points(&m, 3, 2, 11);
            let mut g = rng(12);
            for _ in 0..300 {
                pts.push(Vec3::new(g.random(), g.random(), g.random()));
                nrm.push(Vec3::new(g.random(), g.random(), g.random()) - 0.5);
            }
            pts.extend([Vec3::splat(-0.5), Vec3::splat(1.5)]);
            nrm.extend([Vec3::X, -Vec3::Z]);
            for filter in [Filter::Nearest, Filter::Trilinear] {
                let got = tree.lookup_with_normals(&pts, &nrm, filter).unwrap();
                let cpu = tree.lookup_cpu(&pts, &nrm, filter).unwrap();
                let mut empty = 0;
                for i in 0..pts.len() {
                    let e = (got[i] - cpu[i]).abs().max_element();
                    assert!(
                        e <= ROUNDING,
                        "{name} {filter:?} at {} n {}: {} vs {}",
                        pts[i],
                        nrm[i],
                        got[i],
                        cpu[i]
                    );
                    empty += (cpu[i] == Vec4::ZERO) as usize;
                }
                assert!(empty > 0, "{name}: some random points lie in empty space");
                assert!(got[0].w > 0.99, "{name}: a surface point is stored");
            }
            // The colour of a texel is the marble of a voxel: nearest lookups are exact colours.
            let near = tree
                .lookup_with_normals(&pts[..50], &nrm[..50], Filter::Nearest)
                .unwrap();
            for c in near {
                assert_eq!(c.w, 1.0);
            }
        }
    });
}

/// Dense reference: the trilinear filter of the colour source over the full R³ grid at the
/// same point. A linear colour source (k levels per voxel) is reproduced by the dense filter
/// exactly; the TileTree's bilinear tiles reproduce it exactly in the tile's plane, and along
/// the face axis they take the voxel floor(h) of the surface height h where the dense filter
/// has h − ½: at most ½ voxel, plus the surface's curvature over one texel. Tolerance:
/// k·(½ + ¼) levels. Any seam — a border texel from the wrong surface, a tile of the wrong
/// face, an unfilled texel — would show as errors of many voxels.
#[test]
fn lookups_match_a_dense_reference_across_tile_borders_and_face_switches() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        for (r, sub) in [(64u32, 3u32), (128, 4)] {
            let k = 128 / r;
            let f = linear_colour(k);
            let source = ColourSource::Fn(&f);
            let m = sphere(sub);
            let (tree, _) = build(&kernels, &m, r, &source);
            let map = tree.map_words().unwrap();
            let h = host(tree.plan(), &map);
            // Geometric normals, and the sphere's smooth normals (as a renderer interpolates).
            let (pts, geo) = surface_points(&m, 1, 3, 21);
            let smooth: Vec<Vec3> = pts.iter().map(|&p| (p - 0.5).normalize()).collect();
            let tolerance = k as f32 * 0.75 / 255.0 + 1e-6;
            for normals in [&geo, &smooth] {
                let got = tree
                    .lookup_with_normals(&pts, normals, Filter::Trilinear)
                    .unwrap();
                let (mut border, mut switch, mut worst) = (0, 0, 0f32);
                for (i, &p) in pts.iter().enumerate() {
                    let dense = trilinear_cpu(|v| Some(f(v)), p, r);
                    let e = (got[i] - dense).abs().max_element();
                    worst = worst.max(e);
                    assert!(
                        e <= tolerance,
                        "R={r} at {p} n {}: tiletree {} vs dense {dense} ({} levels)",
                        normals[i],
                        got[i],
                        e * 255.0
                    );
                    let (b, face, _) = footprint_class(&h, p, normals[i]).unwrap();
                    border += b as usize;
                    // A face switch nearby: a small tilt of the normal picks another face.
                    let n = normals[i];
                    let tilted = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z]
                        .iter()
                        .any(|&d| pick_face(0x3f, n + d * 0.1) != face);
                    switch += tilted as usize;
                }
                println!(
                    "R={r}: {} points, {border} straddle a tile border, {switch} near a face switch, worst {:.2} levels (tolerance {:.2})",
                    pts.len(),
                    worst * 255.0,
                    tolerance * 255.0
                );
                assert!(border * 40 > pts.len(), "border cases: {border}");
                assert!(switch * 20 > pts.len(), "face-switch cases: {switch}");
            }
            // No seams: pairs of close points on one triangle whose lookups read different
            // leaves or faces differ no more than the colour function itself plus twice the
            // tolerance.
            let mut g = rng(33);
            let mut across = 0;
            let (a, b): (Vec<Vec3>, Vec<Vec3>) = pts
                .iter()
                .zip(&geo)
                .map(|(&p, &n)| {
                    let d = n.any_orthonormal_vector() * (g.random::<f32>() * 0.6 / r as f32);
                    (p, (p + d - 0.5).normalize() * 0.4 + 0.5)
                })
                .unzip();
            let na: Vec<Vec3> = a.iter().map(|&p| (p - 0.5).normalize()).collect();
            let nb: Vec<Vec3> = b.iter().map(|&p| (p - 0.5).normalize()).collect();
            let ca = tree
                .lookup_with_normals(&a, &na, Filter::Trilinear)
                .unwrap();
            let cb = tree
                .lookup_with_normals(&b, &nb, Filter::Trilinear)
                .unwrap();
            for i in 0..a.len() {
                let (_, fa, la) = footprint_class(&h, a[i], na[i]).unwrap();
                let Some((_, fb, lb)) = footprint_class(&h, b[i], nb[i]) else {
                    continue;
                };
                if fa == fb && la == lb {
                    continue;
                }
                across += 1;
                let change = (b[i] - a[i]).abs() * r as f32 * k as f32 / 255.0;
                let e = (ca[i] - cb[i]).truncate().abs() - change;
                assert!(
                    e.max_element() <= 2.0 * tolerance,
                    "seam between {} and {}: {} vs {}",
                    a[i],
                    b[i],
                    ca[i],
                    cb[i]
                );
            }
            println!("R={r}: {across} close pairs across leaves or faces");
            assert!(across > 50, "pairs across leaves or faces: {across}");
        }
    });
}

/// Marble against its dense trilinear filter: both are convex combinations of voxel colours
/// near the point, so they differ by at most the colour range of the 5³ voxels around it (the
/// tolerance set by the texel size and the colour function's gradient). Every sample point of
/// the bunny, creases included, stays within it.
#[test]
fn marble_lookups_stay_within_the_local_colour_range() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let r = 64;
        let m = unit_mesh("bunny00.off");
        let source = ColourSource::Marble { seed: 3 };
        let (tree, _) = build(&kernels, &m, r, &source);
        let (pts, nrm) = surface_points(&m, 2, 1, 41);
        let got = tree
            .lookup_with_normals(&pts, &nrm, Filter::Trilinear)
            .unwrap();
        let mut over = 0;
        for (i, &p) in pts.iter().enumerate() {
            let dense = trilinear_cpu(|v| Some(marble_rgba8(v, r, 3)), p, r);
            let c = (p * r as f32).floor().as_ivec3();
            let (mut lo, mut hi) = (Vec4::ONE, Vec4::ZERO);
            for z in -2..=2 {
                for y in -2..=2 {
                    for x in -2..=2 {
                        let v = (c + glam::IVec3::new(x, y, z))
                            .clamp(glam::IVec3::ZERO, glam::IVec3::splat(r as i32 - 1));
                        let col = unpack_rgba8(marble_rgba8(v.as_uvec3().to_array(), r, 3));
                        lo = lo.min(col);
                        hi = hi.max(col);
                    }
                }
            }
            let e = (got[i] - dense).abs();
            over += (e.cmpgt(hi - lo + 1e-5)).any() as usize;
        }
        println!(
            "marble: {over} of {} points outside the local range",
            pts.len()
        );
        assert_eq!(over, 0, "points outside the local colour range");
    });
}

#[test]
fn memory_is_the_sum_of_the_buffers_and_the_tile_map_is_written_as_png() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let (tree, _) = build(&kernels, &m, 64, &ColourSource::Marble { seed: 1 });
        let plan = tree.plan();
        let s = tree.stats();
        let want = 4 * (plan.nodes.len() + plan.leaf_records.len()) as u64
            + 4 * s.map_width as u64 * s.map_height as u64;
        assert_eq!(tree.bytes(), want);
        assert_eq!(plan.leaf_records.len(), LEAF_WORDS * s.leaves);
        assert!(
            s.occupancy() > 0.8 && s.occupancy() <= 1.0,
            "{}",
            s.occupancy()
        );
        assert_eq!(s.tiles, plan.tiles.len());
        println!(
            "bunny R=64: {s:?}, occupancy {:.3}, {} bytes",
            s.occupancy(),
            tree.bytes()
        );
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tiles.png");
        tree.write_tile_map_png(&path).unwrap();
        let image = image::open(&path).unwrap().to_rgba8();
        assert_eq!(image.dimensions(), (s.map_width, s.map_height));
        let words = tree.map_words().unwrap();
        assert_eq!(
            image.as_raw().as_slice(),
            bytemuck::cast_slice::<u32, u8>(&words)
        );
        let missing = dir.path().join("no-such-dir").join("tiles.png");
        let err = tree.write_tile_map_png(&missing).unwrap_err().to_string();
        assert!(err.contains("no-such-dir"), "{err}");
    });
}

#[test]
fn bad_input_gets_clear_errors() {
    let m = sphere(1);
    let config = TileTreeConfig::default();
    let err = |r: u32, p: &[Vec3], t: &[[u32; 3]], c: TileTreeConfig| {
        Plan::new(p, t, r, c).err().expect("must fail").to_string()
    };
    let e = err(100, &m.positions, &m.triangles, config);
    assert!(e.contains("power of two") && e.contains("100"), "{e}");
    let e = err(4096, &m.positions, &m.triangles, config);
    assert!(e.contains("4096") && e.contains("2048"), "{e}");
    let e = err(64, &m.positions, &[], config);
    assert!(e.contains("no triangle"), "{e}");
    let e = err(64, &m.positions, &[[0, 1, 999]], config);
    assert!(e.contains("999"), "{e}");
    let e = err(
        64,
        &[Vec3::ZERO, Vec3::X, Vec3::new(2.0, 0.0, 0.0)],
        &[[0, 1, 2]],
        config,
    );
    assert!(e.contains("vertex 2") && e.contains("unit cube"), "{e}");
    let e = err(64, &[Vec3::ZERO, Vec3::X, Vec3::X], &[[0, 1, 2]], config);
    assert!(e.contains("degenerate"), "{e}");
    let bad = TileTreeConfig {
        min_tile: 16,
        max_tile: 8,
        ..config
    };
    let e = err(64, &m.positions, &m.triangles, bad);
    assert!(e.contains("min_tile = 16"), "{e}");
    let wide = TileTreeConfig {
        max_tile: 512,
        ..config
    };
    let e = err(1024, &m.positions, &m.triangles, wide);
    assert!(e.contains("max_tile = 512") && e.contains("256"), "{e}");
    // A map taller than the records' 16-bit coordinates: one 6-texel tile per shelf.
    let narrow = TileTreeConfig {
        max_tile: 4,
        min_tile: 4,
        max_map_width: 6,
    };
    let e = err(512, &sphere(3).positions, &sphere(3).triangles, narrow);
    assert!(e.contains("tile map"), "{e}");

    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let (mut tree, _) = TileTree::build(
            &kernels,
            &m.positions,
            &m.triangles,
            32,
            &ColourSource::Marble { seed: 1 },
            config,
        )
        .unwrap();
        let e = tree
            .lookup(&[Vec3::splat(0.5)], Filter::Nearest)
            .unwrap_err();
        assert!(e.to_string().contains("lookup_with_normals"), "{e}");
        let e = tree
            .lookup_with_normals(&[Vec3::splat(0.5)], &[], Filter::Nearest)
            .unwrap_err();
        assert!(e.to_string().contains("1 points but 0 normals"), "{e}");
        let keys = lazysolid_compute::voxel::VoxelKeys::from_sorted(gpu, "k", &[1]).unwrap();
        let e = tree
            .insert(&keys, &ColourSource::Marble { seed: 1 })
            .unwrap_err();
        assert!(e.to_string().contains("not supported"), "{e}");
    });
}

/// The armadillo at an equivalent 1024³ (thesis Table 4.1: 11.4 MB): sizes and build time for
/// a few tile-size limits. A measurement, not a check: `cargo test -p lazysolid-tests --test
/// tiletree -- --ignored --nocapture`.
#[test]
#[ignore]
fn armadillo_1024_size() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let m = unit_mesh("armadillo.off");
        for (max_tile, min_tile) in [(32, 4), (16, 4), (64, 4), (8, 4)] {
            let config = TileTreeConfig {
                max_tile,
                min_tile,
                ..TileTreeConfig::default()
            };
            let start = std::time::Instant::now();
            let plan = Plan::new(&m.positions, &m.triangles, 1024, config).unwrap();
            let cpu = start.elapsed();
            drop(plan);
            let start = std::time::Instant::now();
            let (tree, _) = TileTree::build(
                &kernels,
                &m.positions,
                &m.triangles,
                1024,
                &ColourSource::Marble { seed: 1 },
                config,
            )
            .unwrap();
            let total = start.elapsed();
            let s = tree.stats();
            let [nodes, leaves, map] = tree.bytes_by_part();
            println!(
                "max_tile {max_tile} min_tile {min_tile}: {:.2} MB (nodes {:.3}, leaves {:.3}, map {:.2} MB), plan {:.2} s, build {:.2} s; {} nodes, {} leaves ({} folded), per depth {:?}, tiles per leaf {:?}, {} tiles, {} texels, map {}x{}, occupancy {:.3}",
                tree.bytes() as f64 / 1e6,
                nodes as f64 / 1e6,
                leaves as f64 / 1e6,
                map as f64 / 1e6,
                cpu.as_secs_f64(),
                total.as_secs_f64(),
                s.nodes,
                s.leaves,
                s.folded_leaves,
                s.leaves_per_depth,
                s.tiles_per_leaf,
                s.tiles,
                s.tile_texels,
                s.map_width,
                s.map_height,
                s.occupancy()
            );
            if max_tile == 32 {
                let dir = std::env::temp_dir().join("lazysolid-armadillo-tiles.png");
                tree.write_tile_map_png(&dir).unwrap();
                // What the texels hold: surface hits, against the surface voxels of a volume.
                let plan = tree.plan();
                let mut hits = 0u64;
                let mut interior = 0u64;
                for tile in &plan.tiles {
                    let [width, height] = tile.stored_size();
                    interior += tile.rect[2] as u64 * tile.rect[3] as u64;
                    for y in 0..height {
                        for x in 0..width {
                            hits += tiletree::texel_voxel(plan, tile, x, y).1 as u64;
                        }
                    }
                }
                let mut v = lazysolid_compute::voxel::Voxelizer::new(gpu).unwrap();
                let voxels = v.surface(&m.positions, &m.triangles, 1024).unwrap().len;
                println!(
                    "  texels: {} in all, {interior} without borders, {hits} with a surface hit; surface voxels at 1024: {voxels}",
                    s.tile_texels
                );
            }
        }
    });
}

/// Two stacked sheets facing +Z, 3.2 voxels apart, fold over one column: the tree splits until
/// they lie in different leaves (T = 4), where a single sheet stays in T = 16 leaves, each tile
/// cropped to the columns the sheet covers.
#[test]
fn folds_split_leaves_until_each_face_projects_injectively() {
    let quad = |z: f32, base: u32| {
        let p = [(0.1, 0.1), (0.9, 0.1), (0.9, 0.9), (0.1, 0.9)].map(|(x, y)| Vec3::new(x, y, z));
        (p, [[base, base + 1, base + 2], [base, base + 2, base + 3]])
    };
    let (a, ta) = quad(0.3, 0);
    let (b, tb) = quad(0.35, 4);
    let config = TileTreeConfig {
        max_tile: 16,
        ..TileTreeConfig::default()
    };
    let one = Plan::new(&a, &ta, 64, config).unwrap();
    assert_eq!(one.stats.leaves_per_depth, vec![0, 0, 16]);
    // The sheet spans columns 6..=57 (0.1 · 64 = 6.4 to 0.9 · 64 = 57.6) along x and y.
    assert_eq!(one.tiles.len(), 16);
    for tile in &one.tiles {
        assert_eq!(tile.face / 2, 2, "a +Z or -Z tile");
        for (k, axis) in [0usize, 1].into_iter().enumerate() {
            let o = tile.origin[axis];
            let (first, last) = (6.max(o), 57.min(o + 15));
            assert_eq!(
                [tile.rect[k], tile.rect[k + 2]],
                [first - o, last - first + 1],
                "tile at {:?}",
                tile.origin
            );
        }
    }
    let positions: Vec<Vec3> = a.iter().chain(&b).copied().collect();
    let triangles: Vec<[u32; 3]> = ta.iter().chain(&tb).copied().collect();
    let two = Plan::new(&positions, &triangles, 64, config).unwrap();
    assert_eq!(two.stats.folded_leaves, 0);
    assert_eq!(*two.stats.leaves_per_depth.last().unwrap(), 2 * 14 * 14);
    assert_eq!(two.stats.leaves_per_depth.len(), 5, "{:?}", two.stats);
    // At T = 4 nothing may split any more: the fold stays, counted.
    let coarse = TileTreeConfig {
        min_tile: 8,
        ..config
    };
    let kept = Plan::new(&positions, &triangles, 64, coarse).unwrap();
    assert!(kept.stats.folded_leaves > 0);
}

/// New surface (the bunny's ears, as the caps of a cut would be) inserted into the TileTree of
/// the rest gets tiles: the re-planned tree equals the tree of the whole surface — same plan,
/// same tile map word for word, the CPU reference's map — with the marble, and with colours
/// from a device buffer (the surface voxels of the whole mesh, looked up on the device); the
/// buffer's tree equals its CPU reference too. A voxel insert is refused, and a bad triangle
/// leaves the tree as it was.
#[test]
fn inserted_surface_gets_tiles_like_the_tree_of_the_whole_surface() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 64;
        let high = |t: &&[u32; 3]| t.iter().map(|&i| m.positions[i as usize].y).sum::<f32>() > 2.1;
        let ears: Vec<[u32; 3]> = m.triangles.iter().filter(high).copied().collect();
        let rest: Vec<[u32; 3]> = m.triangles.iter().filter(|t| !high(t)).copied().collect();
        assert!(
            ears.len() > 100 && rest.len() > 1000,
            "{} {}",
            ears.len(),
            rest.len()
        );
        let whole: Vec<[u32; 3]> = rest.iter().chain(&ears).copied().collect();
        let mut v = lazysolid_compute::voxel::Voxelizer::new(gpu).unwrap();
        let keys = v.surface(&m.positions, &whole, r).unwrap();
        let host_keys = keys.read().unwrap();
        let colours: Vec<u32> = host_keys
            .iter()
            .map(|&k| marble_rgba8(lazysolid_compute::hash::morton_decode(k, 3), r, 5))
            .collect();
        let colours =
            lazysolid_compute::gpu::GpuBuffer::from_slice(gpu, "colours", &colours).unwrap();
        let buffer = ColourSource::Buffer {
            keys: &keys,
            colours: &colours,
        };
        let (pts, nrm) = surface_points(&m, 5, 1, 31);
        for (name, source) in [
            ("marble", ColourSource::Marble { seed: 5 }),
            ("buffer", buffer),
        ] {
            let (mut tree, _) = build_with(&kernels, &m.positions, &rest, r, &source);
            let before = tree.stats().clone();
            let report = tree.insert_surface(&m.positions, &ears, &source).unwrap();
            assert!(
                report.reallocations[0].contains("re-planned"),
                "{name}: {report:?}"
            );
            let (union, _) = build_with(&kernels, &m.positions, &whole, r, &source);
            assert_eq!(tree.stats(), union.stats(), "{name}");
            assert!(tree.stats().tiles > before.tiles, "{name}: new tiles");
            assert_eq!(report.texels, union.stats().tile_texels);
            let map = tree.map_words().unwrap();
            assert!(
                map == union.map_words().unwrap(),
                "{name}: tile maps differ"
            );
            let want = tiletree::fill_cpu(union.plan(), &source.to_host().unwrap());
            let diff = map.iter().zip(&want).filter(|(a, b)| a != b).count();
            assert_eq!(
                diff, 0,
                "{name}: {diff} words differ from the CPU reference"
            );
            for filter in [Filter::Nearest, Filter::Trilinear] {
                let a = tree.lookup_with_normals(&pts, &nrm, filter).unwrap();
                assert_eq!(a, union.lookup_with_normals(&pts, &nrm, filter).unwrap());
                // A buffer source colours only texels that meet the surface: texels that
                // neither meet it nor are reached by the dilation stay 0 (undefined), where
                // the marble colours them from the voxel at the middle of the slab.
                let holes = a.iter().filter(|c| c.w < 0.99).count();
                println!(
                    "{name} {filter:?}: {holes} of {} surface points read undefined texels",
                    a.len()
                );
                let allowed = if name == "buffer" { a.len() / 1000 } else { 0 };
                assert!(
                    holes <= allowed,
                    "{name}: {holes} surface points are not stored"
                );
            }
        }
        // Refusals.
        let source = ColourSource::Marble { seed: 5 };
        let (mut tree, _) = build_with(&kernels, &m.positions, &rest, r, &source);
        assert_eq!(tree.insert_unit(), InsertUnit::Surface);
        let e = tree.insert(&keys, &source).unwrap_err().to_string();
        assert!(e.contains("insert_surface"), "{e}");
        let map = tree.map_words().unwrap();
        let e = tree
            .insert_surface(&m.positions[..3], &[[0, 1, 3]], &source)
            .unwrap_err()
            .to_string();
        assert!(e.contains("indexes past the 3 inserted vertices"), "{e}");
        let e = tree
            .insert_surface(
                &[Vec3::splat(0.5), Vec3::splat(1.5), Vec3::ZERO],
                &[[0, 1, 2]],
                &source,
            )
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside the unit cube"), "{e}");
        assert!(
            tree.map_words().unwrap() == map,
            "refused inserts change nothing"
        );
    });
}

fn build_with(
    kernels: &std::sync::Arc<StoreKernels>,
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    r: u32,
    source: &ColourSource<'_>,
) -> (TileTree, StoreReport) {
    TileTree::build(
        kernels,
        positions,
        triangles,
        r,
        source,
        TileTreeConfig::default(),
    )
    .unwrap()
}
