//! Normal maps filtered by vMF mixtures in the path tracer: the mixture BSDF's sampling agrees
//! with its evaluation (a light found only by BSDF sampling against the same light found by
//! next-event estimation), the finest level of the pyramid shades as the unfiltered map, and the
//! device's EM fit matches the CPU's.

use glam::{DMat3, DVec3};
use lazysolid_renderer::glint::synthetic::{bumps_and_scratches, BumpExtent};
use lazysolid_renderer::glint::NormalExample;
use lazysolid_renderer::normal_map::gpu_fit::GpuVmfFitter;
use lazysolid_renderer::normal_map::pyramid::{level_start, VmfPyramid};
use lazysolid_renderer::normal_map::vmf::{mean_length, VmfLobe};
use lazysolid_renderer::output::Film;
use lazysolid_tests::{render_scene_text, with_gpu};
use std::path::{Path, PathBuf};

fn maps() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/normal-maps")
}

fn grey(c: &[f32; 3]) -> f64 {
    f64::from(c[0] + c[1] + c[2]) / 3.0
}

/// Mean and standard error of the per-pixel difference of two films.
fn difference(a: &Film, b: &Film) -> (f64, f64, f64) {
    let d: Vec<f64> = a
        .color()
        .iter()
        .zip(b.color())
        .map(|(x, y)| grey(x) - grey(y))
        .collect();
    let n = d.len() as f64;
    let mean = d.iter().sum::<f64>() / n;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let level = b.color().iter().map(grey).sum::<f64>() / n;
    (mean, (var / n).sqrt(), level)
}

/// The 100-unit plane of `scenes/normal-maps` with `material`, seen obliquely (footprints of
/// several texels), under `light`.
fn plane_scene(material: &str, light: &str, spp: u32) -> String {
    let plane = maps().join("plane.obj");
    format!(
        r#"
[camera]
position = [0.0, 1.2, 3.0]
look_at = [0.0, 0.0, -3.0]
fov_y = 40.0

[render]
width = 48
height = 32
spp = {spp}
max_depth = 1

[[mesh]]
name = "plane"
path = "{}"
normalize = false

[[mesh]]
name = "lamp"
shape = "quad"

[[material]]
name = "m"
{material}

[[material]]
name = "glow"
kind = "emissive"
emission = [8.0, 8.0, 8.0]

[[instance]]
mesh = "plane"
material = "m"

{light}
"#,
        plane.display()
    )
}

/// A 2×2 one-sided light 3 units above (-1, ·, -3), facing down, as an analytic light (sampled
/// by next-event estimation) or as an emissive quad (found by BSDF sampling only).
const ANALYTIC: &str = "[[light]]\nkind = \"quad\"\ncorner = [-1.0, 3.0, -4.0]\nedge_u = [2.0, 0.0, 0.0]\nedge_v = [0.0, 0.0, 2.0]\nradiance = [8.0, 8.0, 8.0]";
const EMISSIVE: &str = "[[instance]]\nmesh = \"lamp\"\nmaterial = \"glow\"\nscale = 2.0\nrotate = [180.0, 0.0, 0.0]\ntranslate = [-1.0, 3.0, -2.0]";

#[test]
fn the_mixture_bsdf_samples_what_it_evaluates() {
    let dir = tempfile::tempdir().unwrap();
    let grooves = maps().join("v-grooves.png");
    let bumps = maps().join("bumps.png");
    let materials = [
        format!("kind = \"lambertian\"\ncolor = [0.8, 0.8, 0.8]\nnormal_map = \"{}\"", grooves.display()),
        format!(
            "kind = \"conductor\"\npreset = \"silver\"\nroughness = 0.4\nheight_map = \"{}\"\nheight_scale = 6.0",
            bumps.display()
        ),
    ];
    for material in &materials {
        let nee = render_scene_text(dir.path(), &plane_scene(material, ANALYTIC, 96));
        let sampled = render_scene_text(dir.path(), &plane_scene(material, EMISSIVE, 96));
        let (mean, error, level) = difference(&nee, &sampled);
        println!("{material}: NEE − BSDF sampling {mean:.5} ± {error:.5} (image mean {level:.4})");
        assert!(level > 0.01, "the plane is lit ({level})");
        assert!(
            mean.abs() <= 4.0 * error && mean.abs() <= 0.03 * level,
            "{material}: next-event estimation and BSDF sampling differ by {mean} (standard \
             error {error}, image mean {level})"
        );
    }
}

#[test]
fn the_finest_vmf_level_shades_as_the_unfiltered_map() {
    let dir = tempfile::tempdir().unwrap();
    let bumps = maps().join("bumps.png");
    // Close to the plane: footprints well under a texel, where the pyramid's finest level (one
    // sharp lobe per texel) is read.
    let close = |filter: &str| {
        plane_scene(
            &format!(
                "kind = \"lambertian\"\ncolor = [0.8, 0.8, 0.8]\nheight_map = \"{}\"\nheight_scale = 6.0\nnormal_filter = \"{filter}\"",
                bumps.display()
            ),
            ANALYTIC,
            64,
        )
        .replace("position = [0.0, 1.2, 3.0]", "position = [0.0, 0.3, -2.0]")
        .replace("look_at = [0.0, 0.0, -3.0]", "look_at = [0.0, 0.0, -2.3]")
        .replace("fov_y = 40.0", "fov_y = 10.0")
    };
    let unfiltered = render_scene_text(dir.path(), &close("none"));
    let vmf = render_scene_text(dir.path(), &close("vmf"));
    let (mean, error, level) = difference(&vmf, &unfiltered);
    println!("vMF − unfiltered close up: {mean:.5} ± {error:.5} (image mean {level:.4})");
    assert!(
        mean.abs() <= 4.0 * error && mean.abs() <= 0.02 * level,
        "{mean} ± {error}"
    );
    // Pixel by pixel too: the bumps are resolved, so a wrong texel or frame shows.
    let worst = vmf
        .color()
        .iter()
        .zip(unfiltered.color())
        .map(|(a, b)| (grey(a) - grey(b)).abs())
        .fold(0.0f64, f64::max);
    assert!(
        worst < 0.25 * level.max(1e-3) + 0.05,
        "worst pixel difference {worst}"
    );
}

/// The first and second moments of one texel's mixture, `Σ α_j E_j[n]` and `Σ α_j E_j[n nᵀ]`
/// (for a vMF lobe `E[n nᵀ] = (A/κ) I + (1 − 3A/κ) μ μᵀ`): what shading sees of it, and, unlike
/// the lobes one by one, the same however EM splits a texel's mass between coincident lobes
/// (κ up to 1e5 turns f32's last bit of a direction into a percent of a weight).
fn texel_moments(lobes: &[VmfLobe]) -> (DVec3, DMat3) {
    let mut first = DVec3::ZERO;
    let mut second = DMat3::ZERO;
    for l in lobes {
        let a = mean_length(l.kappa);
        let spread = if l.kappa > 1e-6 {
            a / l.kappa
        } else {
            1.0 / 3.0
        };
        first += l.mu * (l.alpha * a);
        second += (DMat3::IDENTITY * spread
            + DMat3::from_cols(l.mu * l.mu.x, l.mu * l.mu.y, l.mu * l.mu.z) * (1.0 - 3.0 * spread))
            * l.alpha;
    }
    (first, second)
}

/// Largest differences between two fits of one level over its texels: of the first and second
/// moments, and of single lobes' weights (informative: see [`texel_moments`]).
fn level_difference(a: &[VmfLobe], b: &[VmfLobe], j: usize) -> (f64, f64, f64) {
    let (mut first, mut second, mut alpha) = (0.0f64, 0.0f64, 0.0f64);
    for (x, y) in a.chunks_exact(j).zip(b.chunks_exact(j)) {
        let ((f1, s1), (f2, s2)) = (texel_moments(x), texel_moments(y));
        first = first.max((f1 - f2).abs().max_element());
        let d = s1 - s2;
        second = second.max(
            d.x_axis
                .abs()
                .max_element()
                .max(d.y_axis.abs().max_element())
                .max(d.z_axis.abs().max_element()),
        );
        for (p, q) in x.iter().zip(y) {
            alpha = alpha.max((p.alpha - q.alpha).abs());
        }
    }
    (first, second, alpha)
}

#[test]
fn the_device_em_fit_matches_the_cpu_fit() {
    let size = 32;
    let heights = bumps_and_scratches(size, 11, BumpExtent::FourSigma);
    let map = NormalExample::from_heights("bumps and scratches", size, &heights).unwrap();
    for j in [2usize, 4] {
        let cpu = VmfPyramid::build(&map, j).unwrap();
        with_gpu(|gpu| {
            let fitter = GpuVmfFitter::new(gpu, &map).unwrap();
            // Level by level from the CPU's own starts: f32 against f64 only.
            for k in 1..cpu.levels.len() {
                let child = &cpu.levels[k - 1];
                let edge = child.size / 2;
                let init: Vec<VmfLobe> = (0..edge * edge)
                    .flat_map(|t| level_start(child, j, t % edge, t / edge))
                    .collect();
                let gpu_level = fitter.fit_level(edge, j, &init).unwrap();
                let (first, second, alpha) =
                    level_difference(&cpu.levels[k].lobes, &gpu_level.lobes, j);
                println!(
                    "J = {j}, level {k}: moments {first:.2e} / {second:.2e}, single weights {alpha:.2e}"
                );
                // Measured 2026-12-05 (lavapipe): at most 1.3e-6 and 2.2e-5.
                assert!(first < 1e-5 && second < 1e-4, "J = {j}, level {k}");
            }
            // The whole pyramid on the device (its starts from its own levels).
            let device = fitter.build(j).unwrap();
            for (k, (c, g)) in cpu.levels.iter().zip(&device.levels).enumerate() {
                let (first, second, alpha) = level_difference(&c.lobes, &g.lobes, j);
                println!(
                    "J = {j}, whole pyramid, level {k}: moments {first:.2e} / {second:.2e}, single weights {alpha:.2e}"
                );
                // Measured 2026-12-05 (lavapipe): at most 4.3e-6 and 4.0e-5.
                assert!(first < 2e-5 && second < 2e-4, "J = {j}, level {k}");
            }
        });
    }
}
