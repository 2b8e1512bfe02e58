//! The glint P-NDF and material: the pruned traversal against the explicit method (the map
//! materialized texel by texel and summed without pruning), the GLSL P-NDF against its CPU
//! twin, importance sampling against its own density and against the evaluated P-NDF (the
//! paper's Fig. 6), and bad material fields.

use glam::{Vec2, Vec3};
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::glint::{build_range_table, GpuGlintMap};
use lazysolid_renderer::glint::{
    BlendMode, ByExampleMap, Footprint, MaterializedMap, NormalExample, RangeTable, SampleTexels,
};
use lazysolid_tests::kernels::render_test::GLINT_PNDF_TEST;
use lazysolid_tests::{bumps_and_scratches, rng, with_gpu, GlintPndfTestPush};
use rand::Rng;

const SIZE: usize = 64;
const PATCH: u32 = 16;
const SEED: u32 = 7;

fn map(mode: BlendMode) -> (ByExampleMap, RangeTable) {
    scaled_map(mode, 1.0)
}

/// The map of the bump field with heights scaled by `scale` (0.1: slopes ten times gentler,
/// normals changing by about 0.03 per texel).
fn scaled_map(mode: BlendMode, scale: f32) -> (ByExampleMap, RangeTable) {
    let h: Vec<f32> = bumps_and_scratches(SIZE, 3)
        .iter()
        .map(|v| v * scale)
        .collect();
    let ex = NormalExample::from_heights("bumps", SIZE, &h).unwrap();
    let table = RangeTable::build(&ex, PATCH);
    (ByExampleMap::new(ex, PATCH, SEED, mode).unwrap(), table)
}

/// Footprints and half vectors: random centres over several patches, widths from under a
/// texel to 6 texels, every other one stretched up to 4× along a random direction (a grazing
/// view's footprint), s near a normal of the footprint (where D_P is large) or anywhere.
fn cases(m: &ByExampleMap, n: usize, seed: u64) -> Vec<(Footprint, Vec2)> {
    let mut r = rng(seed);
    // The stretches come from their own stream, so the other draws are those of isotropic cases.
    let mut stretches = rng(seed + 1000);
    (0..n)
        .map(|i| {
            let sigma = [0.6, 1.5, 3.0, 6.0][i % 4];
            let angle: f32 = stretches.random_range(0.0..std::f32::consts::TAU);
            let factor: f32 = stretches.random_range(0.5..4.0);
            let stretch = if (i / 4) % 2 == 1 {
                Vec2::from_angle(angle) * sigma * factor
            } else {
                Vec2::ZERO
            };
            let fp = Footprint {
                center: Vec2::new(r.random_range(-100.0..100.0), r.random_range(-100.0..100.0)),
                sigma,
                stretch,
            };
            let s = if i % 3 == 0 {
                Vec2::new(r.random_range(-0.6..0.6), r.random_range(-0.6..0.6))
            } else {
                let d = Vec2::new(r.random_range(-2.0..2.0), r.random_range(-2.0..2.0));
                m.point(fp.center + d * fp.sigma).normal
                    + Vec2::new(r.random_range(-0.02..0.02), r.random_range(-0.02..0.02))
            };
            (fp, s)
        })
        .collect()
}

#[test]
fn pruned_pndf_equals_the_explicit_sum() {
    for (mode, scale) in BlendMode::ALL
        .iter()
        .map(|&m| (m, 1.0))
        .chain([(BlendMode::Histogram, 0.1), (BlendMode::None, 0.1)])
    {
        let (m, table) = scaled_map(mode, scale);
        for sigma_r in [0.005f32, 0.02] {
            let (mut worst, mut peak) = (0.0f32, 0.0f32);
            let (mut visited, mut total) = ([0u64; 2], [0u64; 2]);
            for (i, (fp, s)) in cases(&m, 400, 5).into_iter().enumerate() {
                let explicit = MaterializedMap::covering(&m, &fp).pndf(&fp, s, sigma_r);
                let (pruned, stats) = m.pndf(&table, &fp, s, sigma_r);
                let (lo, hi) = fp.texel_box();
                let near = (i % 3 != 0) as usize;
                total[near] += ((hi - lo + 1).x * (hi - lo + 1).y) as u64;
                visited[near] += stats.texels as u64;
                assert!(
                    pruned <= explicit * (1.0 + 1e-5) + 1e-6,
                    "pruning adds mass"
                );
                // Relative to D_P, or to 1 where D_P is below 1 (peaks are in the hundreds
                // to thousands): the tails of elements far from s are what pruning drops.
                let rel = (explicit - pruned) / explicit.max(1.0);
                assert!(
                    rel <= 1e-3,
                    "{mode:?} σ_r {sigma_r} {fp:?} s {s}: explicit {explicit}, pruned {pruned}"
                );
                worst = worst.max(rel);
                peak = peak.max(explicit);
            }
            println!(
                "{mode:?}, heights × {scale}, σ_r {sigma_r}: worst relative loss {worst:.2e}, peak D_P {peak:.1}, texels evaluated: {:.1} % (s anywhere), {:.1} % (s near a normal of the footprint)",
                100.0 * visited[0] as f64 / total[0] as f64,
                100.0 * visited[1] as f64 / total[1] as f64
            );
        }
    }
}

/// Pearson's χ² of `observed` counts against `expected` over bins expecting at least 5, with
/// the rest pooled into one bin: (χ², degrees of freedom).
fn chi2(observed: &[f64], expected: &[f64]) -> (f64, usize) {
    let (mut chi, mut bins, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(expected) {
        if *e >= 5.0 {
            chi += (o - e) * (o - e) / e;
            bins += 1;
        } else {
            pool_o += o;
            pool_e += e;
        }
    }
    if pool_e > 0.0 {
        chi += (pool_o - pool_e) * (pool_o - pool_e) / pool_e.max(5.0);
        bins += 1;
    }
    (chi, bins - 1)
}

/// The upper 1e-3 quantile of χ² with `dof` degrees of freedom (Wilson–Hilferty).
fn chi2_limit(dof: usize) -> f64 {
    let k = dof as f64;
    let z = 3.09; // one-sided 1e-3
    k * (1.0 - 2.0 / (9.0 * k) + z * (2.0 / (9.0 * k)).sqrt()).powi(3)
}

/// Bins of s over [c − r, c + r]², `n` per axis.
struct Bins {
    c: Vec2,
    r: f32,
    n: usize,
}

impl Bins {
    fn index(&self, s: Vec2) -> Option<usize> {
        let t = (s - self.c + self.r) / (2.0 * self.r) * self.n as f32;
        (t.cmpge(Vec2::ZERO).all() && t.cmplt(Vec2::splat(self.n as f32)).all())
            .then(|| t.y as usize * self.n + t.x as usize)
    }

    /// ∫ f over every bin by the midpoint rule on `sub`² points per bin.
    fn integrate(&self, sub: usize, f: impl Fn(Vec2) -> f64) -> Vec<f64> {
        let w = 2.0 * self.r / self.n as f32;
        let area = (w as f64 / sub as f64).powi(2);
        (0..self.n * self.n)
            .map(|b| {
                let corner =
                    self.c - self.r + Vec2::new((b % self.n) as f32, (b / self.n) as f32) * w;
                let mut sum = 0.0;
                for j in 0..sub * sub {
                    let off =
                        Vec2::new((j % sub) as f32 + 0.5, (j / sub) as f32 + 0.5) * w / sub as f32;
                    sum += f(corner + off);
                }
                sum * area
            })
            .collect()
    }
}

/// Importance sampling draws s with exactly the density that MIS weights use: a binned χ²
/// of 400 000 samples from the 4 texels around a point against that density, per mode.
#[test]
fn sampled_half_vectors_follow_the_sampling_density() {
    let mut r = rng(11);
    for mode in BlendMode::ALL {
        let (m, _) = map(mode);
        for sigma_r in [0.01f32, 0.05] {
            let u = Vec2::new(r.random_range(-50.0..50.0), r.random_range(-50.0..50.0));
            let t = SampleTexels::new(&m, u, sigma_r);
            let c = t
                .normals
                .iter()
                .zip(t.weights)
                .fold(Vec2::ZERO, |a, (n, w)| a + *n * w);
            let spread = t
                .normals
                .iter()
                .map(|n| (*n - c).abs().max_element())
                .fold(0.0f32, f32::max);
            let bins = Bins {
                c,
                r: spread + 4.0 * sigma_r + 0.05,
                n: 24,
            };
            let n = 400_000;
            let mut observed = vec![0.0f64; bins.n * bins.n];
            let mut outside = 0.0f64;
            for _ in 0..n {
                let s = t.sample(Vec3::new(r.random(), r.random(), r.random()));
                match bins.index(s) {
                    Some(b) => observed[b] += 1.0,
                    None => outside += 1.0,
                }
            }
            let expected: Vec<f64> = bins
                .integrate(6, |s| t.pdf(s) as f64)
                .iter()
                .map(|p| p * n as f64)
                .collect();
            let inside: f64 = expected.iter().sum();
            let mut o = observed.clone();
            o.push(outside);
            let mut e = expected.clone();
            e.push(n as f64 - inside);
            let (chi, dof) = chi2(&o, &e);
            println!(
                "{mode:?} σ_r {sigma_r}: χ² {chi:.1} over {dof} dof (limit {:.1})",
                chi2_limit(dof)
            );
            assert!(
                chi < chi2_limit(dof),
                "{mode:?} σ_r {sigma_r}: χ² {chi} over {dof} dof"
            );
        }
    }
}

/// The paper's Fig. 6: over a footprint, the half vectors sampled at points u ~ G_P follow
/// the evaluated P-NDF D_P. The sampler's mixture at u smooths the map over one texel like
/// the elements do, but not identically, so the match is measured (relative L1 distance of
/// the binned densities and χ² per degree of freedom) and bounded, not exact.
#[test]
fn sampled_half_vectors_match_the_evaluated_pndf() {
    let mut r = rng(12);
    for mode in [BlendMode::Histogram, BlendMode::None] {
        let (m, table) = scaled_map(mode, 0.3);
        let sigma_r = 0.02;
        let fp = Footprint::isotropic(Vec2::new(37.3, -12.8), 4.0);
        let bins = Bins {
            c: Vec2::ZERO,
            r: 0.5,
            n: 20,
        };
        let n = 300_000;
        let mut observed = vec![0.0f64; bins.n * bins.n];
        for _ in 0..n {
            // u ~ G_P (Box–Muller), then s from the 4 texels around u.
            let (a, b): (f32, f32) = (r.random(), r.random());
            let g = (-2.0 * (1.0 - a).ln()).sqrt() * Vec2::from_angle(std::f32::consts::TAU * b);
            let u = fp.center + g * fp.sigma;
            let s = SampleTexels::new(&m, u, sigma_r).sample(Vec3::new(
                r.random(),
                r.random(),
                r.random(),
            ));
            if let Some(i) = bins.index(s) {
                observed[i] += 1.0;
            }
        }
        let density = bins.integrate(3, |s| m.pndf(&table, &fp, s, sigma_r).0 as f64);
        let mass: f64 = density.iter().sum();
        let seen: f64 = observed.iter().sum();
        let l1: f64 = observed
            .iter()
            .zip(&density)
            .map(|(o, d)| (o / seen - d / mass).abs())
            .sum();
        let expected: Vec<f64> = density.iter().map(|d| d / mass * seen).collect();
        let (chi, dof) = chi2(&observed, &expected);
        println!(
            "{mode:?}: D_P mass in the bins {mass:.4}, samples in the bins {:.4}, relative L1 {l1:.3}, χ²/dof {:.2}",
            seen / n as f64,
            chi / dof as f64
        );
        assert!(l1 < 0.1, "{mode:?}: L1 {l1}");
        assert!(
            (mass - seen / n as f64).abs() < 0.02,
            "{mode:?}: mass {mass} vs {}",
            seen / n as f64
        );
    }
}

/// The GLSL P-NDF (pruned and unpruned), sampling and sampling density against the CPU twin:
/// 2000 cases per mode, D_P within 1e-3 × max(D_P, 1) for 99 % of the cases and 1e-2 for all
/// (D_P moves by |s − n| / σ_r² per unit of normal: the point queries' 1e-5 float differences,
/// amplified by the slope of G⁻¹ in its tails, move it by up to a few 1e-3 at σ_r = 0.01), the pruned sum within the
/// same bound of the unpruned one on the device too, sampled s within 1e-4 and their
/// densities within 1e-3 relative for 99 % of the cases (a texel whose Jacobian jumps at a
/// Gaussianization knot may take the other side on the device).
#[test]
fn gpu_pndf_and_sampling_match_the_cpu_twin() {
    let sigma_r = 0.01f32;
    for mode in BlendMode::ALL {
        let (m, table) = scaled_map(mode, 0.3);
        let mut r = rng(31);
        let cases: Vec<(Footprint, Vec2, Vec2, Vec3)> = cases(&m, 2000, 32)
            .into_iter()
            .map(|(fp, s)| {
                let u = fp.center + Vec2::new(r.random_range(-2.0..2.0), r.random_range(-2.0..2.0));
                (fp, s, u, Vec3::new(r.random(), r.random(), r.random()))
            })
            .collect();
        let flat: Vec<f32> = cases
            .iter()
            .flat_map(|(fp, s, u, x)| {
                [
                    fp.center.x,
                    fp.center.y,
                    fp.sigma,
                    s.x,
                    s.y,
                    u.x,
                    u.y,
                    x.x,
                    x.y,
                    x.z,
                    fp.stretch.x,
                    fp.stretch.y,
                ]
            })
            .collect();
        let out = with_gpu(|gpu| {
            let kernel = gpu.kernel(&GLINT_PNDF_TEST).unwrap();
            let device_map = GpuGlintMap::new(gpu, &m).unwrap();
            let ranges = build_range_table(gpu, m.example(), PATCH).unwrap();
            let input = GpuBuffer::from_slice(gpu, "pndf cases", &flat).unwrap();
            let output = GpuBuffer::<[f32; 6]>::new(gpu, "pndf results", cases.len()).unwrap();
            let push = GlintPndfTestPush {
                map: device_map.params(),
                ranges: ranges.address(),
                cases: input.address(),
                results: output.address(),
                sigma_r,
                n: cases.len() as u32,
            };
            gpu.submit(|rec| {
                rec.dispatch(&kernel, kernel.groups_for(cases.len() as u64), &[], &push)
            })
            .unwrap();
            output.read().unwrap()
        });
        let (mut worst_d, mut worst_s, mut worst_pdf) = (0.0f32, 0.0f32, 0.0f32);
        let (mut loose, mut loose_pdf) = (0usize, 0usize);
        for ((fp, s, u, x), g) in cases.iter().zip(&out) {
            let (cpu, _) = m.pndf(&table, fp, *s, sigma_r);
            let tol = |d: f32| d.max(1.0);
            worst_d = worst_d.max((g[0] - cpu).abs() / tol(cpu));
            assert!(
                (g[0] - cpu).abs() <= 1e-2 * tol(cpu),
                "{mode:?} {fp:?} s {s}: gpu {} cpu {cpu}",
                g[0]
            );
            loose += ((g[0] - cpu).abs() > 1e-3 * tol(cpu)) as usize;
            assert!(
                (g[1] - g[0]).abs() <= 1e-3 * tol(g[1]),
                "{mode:?} {fp:?} s {s}: device pruned {} explicit {}",
                g[0],
                g[1]
            );
            let t = SampleTexels::new(&m, *u, sigma_r);
            let drawn = t.sample(*x);
            let ds = (Vec2::new(g[3], g[4]) - drawn).abs().max_element();
            worst_s = worst_s.max(ds);
            assert!(
                ds <= 1e-4,
                "{mode:?} u {u}: gpu s ({}, {}) cpu {drawn}",
                g[3],
                g[4]
            );
            let pdf = t.pdf(drawn);
            let dp = (g[5] - pdf).abs() / pdf.max(1e-3);
            worst_pdf = worst_pdf.max(dp);
            loose_pdf += (dp > 1e-3) as usize;
        }
        println!("{mode:?}: worst D_P difference {worst_d:.2e} ({loose} of {} over 1e-3), sample {worst_s:.2e}, pdf {worst_pdf:.2e} ({loose_pdf} over 1e-3)", cases.len());
        assert!(
            loose * 100 <= cases.len(),
            "{mode:?}: {loose} cases over 1e-3"
        );
        assert!(
            loose_pdf * 100 <= cases.len(),
            "{mode:?}: {loose_pdf} densities over 1e-3"
        );
    }
}

/// `scenes/glints.toml`.
fn glint_scene_path() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/glints.toml")
}

fn to_rgb8(film: &lazysolid_renderer::output::Film) -> image::RgbImage {
    use lazysolid_renderer::output::{Operator, ToneMap};
    let t = ToneMap {
        exposure_ev: 0.0,
        operator: Operator::AcesFitted,
    };
    lazysolid_renderer::output::tonemapped_rgb8(film, &t).unwrap()
}

/// Largest FLIP mean between the glint scene rendered with the pruned P-NDF and with the
/// explicit reference (every texel of each footprint, no pruning) on the device path tracer,
/// same samples: the P-NDFs differ by at most 1e-3 × max(D_P, 1), so only the paths that
/// Russian roulette ends differently can differ.
const GLINT_FLIP_LIMIT: f32 = 0.01;

/// The glint scene (64 × 48, 4 spp) with the pruned traversal against the explicit reference
/// on the device path tracer, and both against the plain conductor (which must differ: the
/// glints are seen).
#[test]
fn glint_scene_matches_its_explicit_reference() {
    use lazysolid_renderer::diff::flip_images;
    use lazysolid_renderer::glint::{render_glint_cases, GlintCase};
    use lazysolid_renderer::scene::Scene;
    let mut scene = Scene::load(&glint_scene_path()).unwrap();
    scene.render.width = 64;
    scene.render.height = 48;
    scene.render.spp = 4;
    let out = with_gpu(|gpu| render_glint_cases(gpu, &scene, &GlintCase::ALL).unwrap());
    let [pruned, explicit, conductor] = &out[..] else {
        panic!("three cases")
    };
    let report = flip_images(&to_rgb8(&explicit.film), &to_rgb8(&pruned.film)).unwrap();
    let versus_plain = flip_images(&to_rgb8(&conductor.film), &to_rgb8(&pruned.film)).unwrap();
    println!(
        "pruned vs explicit: FLIP mean {:.5}, p95 {:.5}, max {:.5}; vs the plain conductor {:.4}; time pruned {:?}, explicit {:?}, conductor {:?}",
        report.mean, report.p95, report.max, versus_plain.mean, pruned.time, explicit.time, conductor.time
    );
    assert!(report.mean <= GLINT_FLIP_LIMIT, "FLIP mean {}", report.mean);
    assert!(
        versus_plain.mean > 5.0 * report.mean.max(1e-3),
        "glints not seen: {}",
        versus_plain.mean
    );
}

/// Writes a PNG of `w` × `h` RGB pixels `rgb(x, y)` under a temporary folder.
fn png(dir: &std::path::Path, name: &str, w: u32, h: u32, rgb: impl Fn(u32, u32) -> [u8; 3]) {
    image::RgbImage::from_fn(w, h, |x, y| image::Rgb(rgb(x, y)))
        .save(dir.join(name))
        .unwrap();
}

/// A glint scene in `dir` whose material table is `material` (the rest is fixed).
fn parse_glint(dir: &std::path::Path, material: &str) -> Result<(), String> {
    let text = format!(
        r#"
[camera]
position = [0, 1, 3]
look_at = [0, 0, 0]
fov_y = 40

[render]
width = 8
height = 8
spp = 1

[[mesh]]
name = "q"
shape = "quad"

[[material]]
name = "m"
{material}

[[instance]]
mesh = "q"
material = "m"
"#
    );
    lazysolid_renderer::scene::Scene::parse(&text, &dir.join("scene.toml"))
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// Bad example maps and bad fields: each message names the scene file and line, the field,
/// and the file, texel or limit.
#[test]
fn bad_glint_materials_get_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    png(d, "flat.png", 32, 32, |_, _| [128, 128, 255]);
    png(d, "wide.png", 48, 32, |_, _| [128, 128, 255]);
    png(d, "tiny.png", 4, 4, |_, _| [128, 128, 255]);
    png(d, "steep.png", 16, 16, |x, y| {
        if (x, y) == (3, 5) {
            [255, 255, 255]
        } else {
            [128, 128, 255]
        }
    });
    let good = r#"kind = "glint"
preset = "silver"
normal_map = "flat.png"
intrinsic_roughness = 0.01
scale = 0.1
uv = "planar""#;
    assert_eq!(parse_glint(d, good), Ok(()));
    // A map of any size is fitted as an exemplar is: 48×32 is cut to its centre 32².
    assert_eq!(
        parse_glint(d, &good.replace("flat.png", "wide.png")),
        Ok(())
    );
    let cases: [(String, &[&str]); 11] = [
        (
            good.replace("normal_map = \"flat.png\"\n", ""),
            &["material \"m\".normal_map", "missing", "PNG"],
        ),
        (
            good.replace("flat.png", "nowhere.png"),
            &["normal_map", "nowhere.png", "does not exist"],
        ),
        (
            good.replace("flat.png", "tiny.png"),
            &["tiny.png", "4x4", "8 to 2048"],
        ),
        (
            good.replace("flat.png", "steep.png"),
            &["steep.png", "column 3, row 5", "n_x² + n_y² <= 1"],
        ),
        (
            good.replace("0.01", "0.9"),
            &["intrinsic_roughness", "0.9", "[0.001, 0.5]"],
        ),
        (
            good.replace("intrinsic_roughness = 0.01\n", ""),
            &["intrinsic_roughness", "missing"],
        ),
        (good.replace("scale = 0.1", "scale = -1"), &["scale", "> 0"]),
        (
            good.replace("uv = \"planar\"", ""),
            &["uv", "missing", "planar", "spherical"],
        ),
        (
            format!("{good}\npatch = 6"),
            &["patch", "power of two", "2 to 8"],
        ),
        (
            format!("{good}\nroughness = 0.2"),
            &["roughness", "does not apply to a glint", "conductor"],
        ),
        (
            format!("{good}\nheight_map = \"flat.png\""),
            &["height_map", "exclusive"],
        ),
    ];
    for (material, needles) in cases {
        let e = parse_glint(d, &material).expect_err(&material);
        println!("{e}");
        assert!(e.contains("scene.toml:"), "{e}");
        for n in needles {
            assert!(e.contains(n), "`{n}` not in: {e}");
        }
    }
}
