//! Normal maps filtered by vMF mixtures in the path tracer: the mixture BSDF's sampling agrees
//! with its evaluation (a light found only by BSDF sampling against the same light found by
//! next-event estimation), and the finest level of the pyramid shades as the unfiltered map.

use lazysolid_renderer::output::Film;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use lazysolid_tests::with_gpu;
use std::path::{Path, PathBuf};

fn maps() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/normal-maps")
}

fn render(dir: &Path, text: &str) -> Film {
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    with_gpu(|gpu| {
        let mut t = PathTracer::new(gpu, &scene).unwrap();
        t.render(|_| {}).unwrap()
    })
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
        let nee = render(dir.path(), &plane_scene(material, ANALYTIC, 96));
        let sampled = render(dir.path(), &plane_scene(material, EMISSIVE, 96));
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
    let unfiltered = render(dir.path(), &close("none"));
    let vmf = render(dir.path(), &close("vmf"));
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
