//! The glint microstructure by example: the GLSL point query (run by
//! `glsl/render_test/glint_test.comp`) against its CPU twin, the Jacobians against finite
//! differences, the map's continuity across target-patch borders, the device-built range table
//! against its CPU build and brute force, conservative blended ranges, and bad input.
//!
//! Tolerances: GPU and CPU normals within 1e-5 absolute, Jacobians within 1e-4 × max(1, |J|)
//! (the same f32 operations in the same order; lavapipe may fuse multiply-adds). A Jacobian
//! may jump where an input sits on a texel edge or a Gaussianization-table knot; such points
//! are recognized by nudging the CPU query and must stay under 1 %. Range tables agree
//! exactly (integers). Blended ranges must contain every point value within 1e-5, a third of a
//! 16-bit quantization step, for float rounding in the blend.

use glam::{Mat2, Vec2};
use lazysolid_compute::gpu::{Gpu, GpuBuffer};
use lazysolid_renderer::glint::{
    build_range_table, BlendMode, ByExampleMap, GlintError, GpuGlintMap, NormalExample, RangeTable,
};
use lazysolid_tests::kernels::render_test::GLINT_TEST;
use lazysolid_tests::{bumps_and_scratches, rng, with_gpu, GlintTestPush};
use rand::Rng;

/// Example edge of the tests (the paper's examples are 512²; the blend does not depend on it).
const SIZE: usize = 64;
/// Target patch edge: a quarter of the example, as in the paper.
const PATCH: u32 = 16;
const SEED: u32 = 7;

fn example(seed: u64) -> NormalExample {
    NormalExample::from_heights(
        "bumps and scratches",
        SIZE,
        &bumps_and_scratches(SIZE, seed),
    )
    .unwrap()
}

fn map(mode: BlendMode) -> ByExampleMap {
    ByExampleMap::new(example(3), PATCH, SEED, mode).unwrap()
}

fn random_points(n: usize, seed: u64) -> Vec<Vec2> {
    let mut r = rng(seed);
    (0..n)
        .map(|_| Vec2::new(r.random_range(-300.0..300.0), r.random_range(-300.0..300.0)))
        .collect()
}

fn run_points(gpu: &Gpu, map: &ByExampleMap, points: &[Vec2]) -> Vec<[f32; 10]> {
    let kernel = gpu.kernel(&GLINT_TEST).unwrap();
    let device_map = GpuGlintMap::new(gpu, map).unwrap();
    let pts: Vec<[f32; 2]> = points.iter().map(|p| p.to_array()).collect();
    let input = GpuBuffer::from_slice(gpu, "glint points", &pts).unwrap();
    let output = GpuBuffer::<[f32; 10]>::new(gpu, "glint results", points.len()).unwrap();
    let push = GlintTestPush {
        map: device_map.params(),
        points: input.address(),
        results: output.address(),
        n: points.len() as u32,
    };
    gpu.submit(|rec| rec.dispatch(&kernel, kernel.groups_for(points.len() as u64), &[], &push))
        .unwrap();
    output.read().unwrap()
}

fn max_abs(m: Mat2) -> f32 {
    m.to_cols_array().iter().fold(0.0f32, |a, v| a.max(v.abs()))
}

fn mat_close(a: Mat2, b: Mat2, tol: f32) -> bool {
    max_abs(a - b) <= tol * max_abs(a).max(1.0)
}

/// Whether the CPU Jacobian at `u` jumps within 1e-3 texels (a texel edge or a table knot):
/// by more than 2e-3 × max(1, |J|), far more than its smooth variation over that step.
fn jacobian_is_sensitive(map: &ByExampleMap, u: Vec2) -> bool {
    let q = map.point(u);
    [Vec2::X, Vec2::Y, -Vec2::X, -Vec2::Y].iter().any(|d| {
        let n = map.point(u + *d * 1e-3);
        !mat_close(q.jacobian, n.jacobian, 2e-3)
            || !mat_close(q.jacobian_exact, n.jacobian_exact, 2e-3)
    })
}

#[test]
fn point_queries_match_the_cpu_twin() {
    let points = random_points(4096, 21);
    let maps: Vec<ByExampleMap> = BlendMode::ALL.iter().map(|&m| map(m)).collect();
    let out = with_gpu(|gpu| {
        maps.iter()
            .map(|m| run_points(gpu, m, &points))
            .collect::<Vec<_>>()
    });
    for (m, gpu_out) in maps.iter().zip(&out) {
        let (mut failures, mut sensitive) = (Vec::new(), 0);
        for (u, g) in points.iter().zip(gpu_out) {
            let q = m.point(*u);
            let normal = Vec2::new(g[0], g[1]);
            let jac = Mat2::from_cols_array(&[g[2], g[3], g[4], g[5]]);
            let exact = Mat2::from_cols_array(&[g[6], g[7], g[8], g[9]]);
            if (normal - q.normal).abs().max_element() > 1e-5 {
                failures.push(format!("normal at {u}: cpu {} gpu {normal}", q.normal));
            } else if !mat_close(q.jacobian, jac, 1e-4) || !mat_close(q.jacobian_exact, exact, 1e-4)
            {
                if jacobian_is_sensitive(m, *u) {
                    sensitive += 1;
                } else {
                    failures.push(format!("jacobian at {u}: cpu {:?} gpu {jac:?}", q.jacobian));
                }
            }
        }
        assert!(
            failures.is_empty(),
            "{:?}: {} of {} differ, e.g. {:#?}",
            m.mode(),
            failures.len(),
            points.len(),
            &failures[..failures.len().min(5)]
        );
        assert!(
            sensitive <= points.len() / 100,
            "{:?}: {sensitive} sensitive points",
            m.mode()
        );
    }
}

/// Central differences of the CPU map, with a step of 1e-3 texels: within it the Jacobian
/// varies smoothly unless [`jacobian_is_sensitive`] says otherwise.
fn finite_difference(map: &ByExampleMap, u: Vec2) -> Mat2 {
    let h = 1e-3;
    let d = |e: Vec2| (map.point(u + e * h).normal - map.point(u - e * h).normal) / (2.0 * h);
    Mat2::from_cols(d(Vec2::X), d(Vec2::Y))
}

#[test]
fn jacobians_match_finite_differences_except_the_weight_term() {
    let points = random_points(2000, 22);
    for mode in BlendMode::ALL {
        let m = map(mode);
        let (mut failures, mut checked, mut sensitive) = (Vec::new(), 0, 0);
        let (mut paper_error, mut weight_term) = (0.0f32, 0.0f32);
        for &u in &points {
            // Skip points whose stencil crosses a texel edge (the bilinear Jacobian jumps there;
            // every corner's example position has the fractional part of u), a cell border or
            // (without blending) a change of nearest vertex (both at integer u), or a table knot
            // (the nudges of `jacobian_is_sensitive` are the stencil's points).
            let frac = u - u.floor();
            if frac.min_element() < 2e-3
                || frac.max_element() > 1.0 - 2e-3
                || jacobian_is_sensitive(&m, u)
            {
                sensitive += 1;
                continue;
            }
            checked += 1;
            let q = m.point(u);
            let fd = finite_difference(&m, u);
            if max_abs(q.jacobian_exact - fd) > 2e-3 + 1e-2 * max_abs(fd) {
                failures.push(format!("{u}: exact {:?} fd {fd:?}", q.jacobian_exact));
            }
            paper_error = paper_error.max(max_abs(q.jacobian - fd));
            weight_term = weight_term.max(max_abs(q.jacobian - q.jacobian_exact));
        }
        assert!(
            failures.is_empty(),
            "{mode:?}: {} of {checked} differ, e.g. {:#?}",
            failures.len(),
            &failures[..failures.len().min(5)]
        );
        assert!(
            checked >= points.len() / 2,
            "{mode:?}: only {checked} points away from edges and knots ({sensitive} skipped)"
        );
        // The paper's Jacobian (Eqs. 10-12) misses Σ y_i ∂c_i/∂u, which is zero only without
        // blending; it stays of the order of the normals' spread over l.
        if mode == BlendMode::None {
            assert_eq!(weight_term, 0.0);
        } else {
            assert!(
                paper_error > 1e-3,
                "{mode:?}: the weight term vanished ({paper_error})"
            );
            if mode != BlendMode::Histogram {
                assert!(
                    paper_error < 8.0 * 2.0 / PATCH as f32,
                    "{mode:?}: {paper_error}"
                );
            }
        }
        eprintln!("{mode:?}: {checked} points checked, {sensitive} skipped, paper Jacobian max error {paper_error}, weight term up to {weight_term}");
    }
}

#[test]
fn the_map_is_continuous_across_target_patch_borders() {
    let mut r = rng(23);
    for mode in [BlendMode::Linear, BlendMode::Variance, BlendMode::Histogram] {
        let m = map(mode);
        for _ in 0..500 {
            let k = r.random_range(-20..20) as f32 * PATCH as f32;
            let t: f32 = r.random_range(-300.0..300.0);
            let e = 1e-3;
            for (a, b) in [
                (Vec2::new(k - e, t), Vec2::new(k + e, t)),
                (Vec2::new(t, k - e), Vec2::new(t, k + e)),
            ] {
                let d = (m.point(a).normal - m.point(b).normal).abs().max_element();
                // A jump of a patch seam would be of the order of the normals' spread (~0.1).
                assert!(d < 2e-2, "{mode:?}: jump {d} between {a} and {b}");
            }
        }
    }
}

/// Min/max of the quantized texels over [x, x + edge]², by brute force.
fn brute_force(ex: &NormalExample, x: usize, y: usize, edge: usize) -> [u32; 2] {
    let q = lazysolid_renderer::glint::range_table::quantize_texels(ex);
    let (mut lo, mut hi) = ([u32::MAX; 2], [0u32; 2]);
    for yy in y..=y + edge {
        for xx in x..=x + edge {
            let e = q[yy * ex.size() + xx];
            lo = [lo[0].min(e[0] & 0xFFFF), lo[1].min(e[0] >> 16)];
            hi = [hi[0].max(e[1] & 0xFFFF), hi[1].max(e[1] >> 16)];
        }
    }
    [lo[0] | lo[1] << 16, hi[0] | hi[1] << 16]
}

#[test]
fn range_tables_are_exact_and_built_alike_on_the_device() {
    let examples = [example(3), example(4)];
    let device: Vec<Vec<[u32; 2]>> = with_gpu(|gpu| {
        examples
            .iter()
            .map(|e| build_range_table(gpu, e, PATCH).unwrap().read().unwrap())
            .collect()
    });
    for (ex, dev) in examples.iter().zip(device) {
        let cpu = RangeTable::build(ex, PATCH);
        assert_eq!(cpu.levels(), 5);
        assert_eq!(cpu.bytes(), 5 * (SIZE * SIZE * 8) as u64);
        let first_diff = cpu.entries().iter().zip(&dev).position(|(a, b)| a != b);
        assert_eq!(first_diff, None, "device table differs from the CPU build");
        assert_eq!(RangeTable::from_entries(SIZE, 5, dev), cpu);
        let mut stored = 0;
        for level in 0..cpu.levels() {
            let edge = 1usize << level;
            for y in 0..SIZE {
                for x in 0..SIZE {
                    let e = cpu.packed(level, x, y);
                    if x + edge < SIZE && y + edge < SIZE {
                        assert_eq!(
                            e,
                            brute_force(ex, x, y, edge),
                            "level {level} at ({x}, {y})"
                        );
                        stored += 1;
                    } else {
                        assert!(cpu.query(level, x, y).is_none());
                    }
                }
            }
        }
        assert_eq!(
            stored,
            (0..5).map(|k| (SIZE - (1 << k)).pow(2)).sum::<usize>()
        );
        // Quantization rounds outward: every texel lies inside its level-0 cells' intervals.
        for y in 0..SIZE - 1 {
            for x in 0..SIZE - 1 {
                let i = cpu.query(0, x, y).unwrap();
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    assert!(i.contains(ex.texel(x + dx, y + dy), 0.0));
                }
            }
        }
    }
}

#[test]
fn blended_ranges_contain_every_point_of_their_square() {
    let mut r = rng(24);
    for mode in BlendMode::ALL {
        let m = map(mode);
        let table = RangeTable::build(m.example(), PATCH);
        let mut widths = vec![(0.0f32, 0usize); table.levels()];
        for _ in 0..1000 {
            let level = r.random_range(0..table.levels());
            let edge = 1u32 << level;
            let cell = (r.random_range(-30i64..30), r.random_range(-30i64..30));
            let x = cell.0 * PATCH as i64 + r.random_range(0..=(PATCH - edge) as i64);
            let y = cell.1 * PATCH as i64 + r.random_range(0..=(PATCH - edge) as i64);
            let range = m.range(&table, x, y, edge).unwrap();
            let w = &mut widths[level];
            w.0 += (range.hi - range.lo).max_element();
            w.1 += 1;
            let corner = Vec2::new(x as f32, y as f32);
            // Random points and the square's corners (the weights' extremes).
            let mut pts: Vec<Vec2> = (0..64)
                .map(|_| corner + Vec2::new(r.random::<f32>(), r.random::<f32>()) * edge as f32)
                .collect();
            let far = edge as f32 * (1.0 - 1e-6);
            pts.extend(
                [
                    Vec2::ZERO,
                    Vec2::new(far, 0.0),
                    Vec2::new(0.0, far),
                    Vec2::splat(far),
                ]
                .map(|d| corner + d),
            );
            for p in pts {
                let n = m.point(p).normal;
                assert!(
                    range.contains(n, 1e-5),
                    "{mode:?}: {n} at {p} outside {range:?} of the square ({x}, {y}) edge {edge}"
                );
            }
        }
        // Intervals tighten towards single cells (otherwise the traversal could never prune).
        let mean = |l: usize| widths[l].0 / widths[l].1.max(1) as f32;
        assert!(
            mean(0) < 0.5 * mean(table.levels() - 1),
            "{mode:?}: {widths:?}"
        );
        eprintln!(
            "{mode:?}: mean interval width per level {:?}",
            (0..table.levels()).map(mean).collect::<Vec<_>>()
        );
    }
}

#[test]
fn bad_examples_patches_and_squares_are_refused() {
    let err =
        NormalExample::from_normals("leather.png", 48, vec![Vec2::ZERO; 48 * 48]).unwrap_err();
    assert!(matches!(err, GlintError::Size { .. }));
    let text = err.to_string();
    assert!(
        text.contains("leather.png") && text.contains("48x48") && text.contains("2048"),
        "{text}"
    );
    let err = NormalExample::from_normals("leather.png", 16, vec![Vec2::ZERO; 200]).unwrap_err();
    assert!(err.to_string().contains("200 given"), "{err}");
    let mut texels = vec![Vec2::ZERO; 256];
    texels[3 * 16 + 5] = Vec2::new(0.9, 0.9);
    let text = NormalExample::from_normals("flakes.png", 16, texels.clone())
        .unwrap_err()
        .to_string();
    assert!(
        text.contains("flakes.png") && text.contains("column 5, row 3") && text.contains("<= 1"),
        "{text}"
    );
    texels[3 * 16 + 5] = Vec2::new(f32::NAN, 0.0);
    assert!(matches!(
        NormalExample::from_normals("flakes.png", 16, texels).unwrap_err(),
        GlintError::Texel { x: 5, y: 3, .. }
    ));
    let mut heights = vec![0.0; 256];
    heights[17] = f32::INFINITY;
    let text = NormalExample::from_heights("scratches.png", 16, &heights)
        .unwrap_err()
        .to_string();
    assert!(
        text.contains("scratches.png") && text.contains("column 1, row 1") && text.contains("inf"),
        "{text}"
    );
    for patch in [0, 3, 32] {
        let text = ByExampleMap::new(example(3), patch, 0, BlendMode::Linear)
            .unwrap_err()
            .to_string();
        assert!(
            text.contains(&format!("edge {patch}")) && text.contains("16"),
            "{text}"
        );
    }
    let m = map(BlendMode::Histogram);
    let table = RangeTable::build(m.example(), PATCH);
    for (x, y, edge, says) in [
        (0, 0, 3, "power of two"),
        (0, 0, 32, "power of two"),
        (12, 0, 8, "crosses"),
        (-4, -3, 4, "crosses"),
    ] {
        let text = m.range(&table, x, y, edge).unwrap_err().to_string();
        assert!(
            text.contains(says) && text.contains(&format!("edge {edge}")),
            "{text}"
        );
    }
    let small = RangeTable::build(m.example(), 4);
    let text = m.range(&small, 0, 0, 8).unwrap_err().to_string();
    assert!(text.contains("3 levels"), "{text}");
}
