//! Light transport of the path tracer against answers known in closed form: analytic lights
//! occlude like the emissive meshes of the same shape, every path length up to `max_depth` is
//! counted once, plastic conserves energy, and a glass slab transmits what the Fresnel series
//! of its two faces says.
//!
//! Each test judges a mean over many pixels against its standard error, estimated from the
//! spread of the pixels themselves (each pixel is an independent estimate of the same value,
//! or of a difference that is zero when the two renders agree).

use glam::{Affine3A, Vec3};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_renderer::output::Film;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{
    Camera, Environment, Instance, Lens, Light, Material, MaterialKind, RenderSettings, Scene,
    SceneMesh,
};
use lazysolid_tests::with_gpu;
use std::path::PathBuf;

fn material(kind: MaterialKind, color: Vec3) -> Material {
    Material {
        name: format!("{kind:?}"),
        kind,
        color,
        k: Vec3::ZERO,
        emission: Vec3::ZERO,
        roughness: 0.0,
        ior: 1.5,
        texture: None,
        glint: None,
        albedo_map: None,
        normal_map: None,
    }
}

fn emissive(radiance: f32) -> Material {
    Material {
        emission: Vec3::splat(radiance),
        ..material(MaterialKind::Emissive, Vec3::ZERO)
    }
}

/// A scene of `objects` (each mesh with its own material, placed as given) seen by `camera`.
fn scene(
    objects: Vec<(Mesh, Material)>,
    lights: Vec<Light>,
    environment: f32,
    camera: Camera,
    render: RenderSettings,
) -> Scene {
    let mut s = Scene {
        source: PathBuf::from("light transport (built in the test)"),
        camera,
        render,
        meshes: Vec::new(),
        materials: Vec::new(),
        instances: Vec::new(),
        lights,
        environment: Environment::Constant(Vec3::splat(environment)),
        explosion: None,
        animation: None,
    };
    for (i, (mesh, m)) in objects.into_iter().enumerate() {
        s.meshes.push(SceneMesh {
            name: format!("mesh {i}"),
            mesh,
            cut_from: None,
        });
        s.materials.push(m);
        s.instances.push(Instance {
            mesh: i,
            material: i,
            transform: Affine3A::IDENTITY,
            piece: None,
        });
    }
    s
}

fn camera(position: Vec3, look_at: Vec3, fov_y_deg: f32) -> Camera {
    Camera {
        position,
        look_at,
        up: Vec3::Y,
        fov_y_deg,
        lens: Lens::Pinhole,
    }
}

/// `side`² pixels, `spp` samples, no Russian roulette (it would only add noise here).
fn settings(side: u32, spp: u32, max_depth: u32) -> RenderSettings {
    RenderSettings {
        width: side,
        height: side,
        spp,
        max_depth,
        rr_depth: max_depth,
        seed: 7,
    }
}

fn render(scene: &Scene) -> Film {
    with_gpu(|gpu| {
        let mut t = PathTracer::new(gpu, scene).unwrap();
        t.render(|_| {}).unwrap()
    })
}

/// Mean of the pixels' grey values and its standard error.
fn mean_and_error(values: &[f32]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().map(|&v| v as f64).sum::<f64>() / n;
    let var = values
        .iter()
        .map(|&v| (v as f64 - mean).powi(2))
        .sum::<f64>()
        / (n - 1.0);
    (mean, (var / n).sqrt())
}

fn grey(c: &[f32; 3]) -> f32 {
    (c[0] + c[1] + c[2]) / 3.0
}

/// The parallelogram `corner + s·u + t·v` as two triangles facing u × v.
fn parallelogram(corner: Vec3, u: Vec3, v: Vec3) -> Mesh {
    Mesh {
        positions: vec![corner, corner + u, corner + u + v, corner + v],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        uvs: None,
        source: "parallelogram".into(),
    }
}

/// Analytic one-sided quad lights, one above the other, over a Lambertian floor under a dim
/// sky, against emissive meshes of the same shape and radiance. The lower light shadows the
/// upper one and both shadow the sky: next-event estimation (the analytic lights' only
/// difference) must see that. Per pixel the difference of the two renders has mean zero when
/// they agree; over the pixels under the lights and over the whole floor its mean must lie
/// within 4 standard errors of zero.
#[test]
fn analytic_lights_occlude_like_emissive_meshes() {
    let floor = parallelogram(
        Vec3::new(-20.0, 0.0, -20.0),
        Vec3::new(0.0, 0.0, 40.0),
        Vec3::new(40.0, 0.0, 0.0),
    );
    // (corner, u, v, radiance): u × v = −y, both emit downwards.
    let quads = [
        (Vec3::new(-1.0, 1.6, -1.0), 2.0, 1.0f32),
        (Vec3::new(-0.3, 0.8, -0.3), 0.6, 3.0),
    ];
    let edges = |size: f32| (Vec3::new(size, 0.0, 0.0), Vec3::new(0.0, 0.0, size));
    let view = camera(Vec3::new(0.0, 0.7, 3.5), Vec3::new(0.0, 0.0, 0.0), 40.0);
    let lambertian = material(MaterialKind::Lambertian, Vec3::splat(0.5));
    let render_settings = settings(48, 128, 3);
    let analytic = scene(
        vec![(floor.clone(), lambertian.clone())],
        quads
            .iter()
            .map(|&(corner, size, radiance)| {
                let (u, v) = edges(size);
                Light::Quad {
                    corner,
                    edge_u: u,
                    edge_v: v,
                    radiance: Vec3::splat(radiance),
                    two_sided: false,
                }
            })
            .collect(),
        0.2,
        view,
        render_settings,
    );
    let mut objects = vec![(floor, lambertian)];
    for &(corner, size, radiance) in &quads {
        let (u, v) = edges(size);
        objects.push((parallelogram(corner, u, v), emissive(radiance)));
    }
    let meshes = scene(objects, vec![], 0.2, view, render_settings);
    let (a, b) = (render(&analytic), render(&meshes));

    // The floor point each pixel centre sees, for the region under the lights.
    let forward = (view.look_at - view.position).normalize();
    let right = forward.cross(view.up).normalize();
    let up = right.cross(forward);
    let tan_half = (view.fov_y_deg.to_radians() * 0.5).tan();
    let side = render_settings.width as f32;
    let floor_point = |i: usize| -> Option<Vec3> {
        let (x, y) = ((i % 48) as f32 + 0.5, (i / 48) as f32 + 0.5);
        let d = forward
            + right * tan_half * (x / side * 2.0 - 1.0)
            + up * tan_half * (1.0 - y / side * 2.0);
        let t = -view.position.y / d.y;
        (t > 0.0).then(|| view.position + d * t)
    };
    let mut under = Vec::new();
    let mut all = Vec::new();
    for (i, (ca, cb)) in a.color().iter().zip(b.color()).enumerate() {
        let Some(p) = floor_point(i) else { continue };
        let d = grey(ca) - grey(cb);
        all.push(d);
        if p.x.abs() < 1.0 && p.z.abs() < 1.0 {
            under.push(d);
        }
    }
    let mean_b = b.color().iter().map(grey).sum::<f32>() / b.len() as f32;
    for (region, diffs) in [("under the lights", &under), ("floor", &all)] {
        let (mean, error) = mean_and_error(diffs);
        println!(
            "{region}: analytic − emissive mesh {mean:.5} ± {error:.5} over {} pixels \
             (image mean {mean_b:.4})",
            diffs.len()
        );
        assert!(
            mean.abs() <= 4.0 * error,
            "{region}: analytic lights differ from emissive meshes by {mean} (standard error \
             {error})"
        );
    }
    assert!(under.len() > 200, "{} pixels under the lights", under.len());
}

/// A closed Lambertian sphere of albedo a (radius R) around a sphere light of radius r and
/// radiance L at its centre, seen from inside. With s = (r/R)², the light gives every wall
/// point a·L·s at the first bounce, and each further bounce multiplies the wall's radiance by
/// a·(1 − s) (the light hides the share s of the cosine-weighted hemisphere). A path of at
/// most k bounces therefore sees a·L·s·(1 − (a(1 − s))^k) / (1 − a(1 − s)) on the wall: 0 at
/// k = 0, where only emitters are seen.
#[test]
fn max_depth_counts_every_path_length_once() {
    let (albedo, radiance, r) = (0.8f32, 25.0f32, 0.1f32);
    let big_r = 0.5f32;
    let s = (r / big_r).powi(2);
    let shell = Mesh::icosphere(5);
    let view = camera(Vec3::new(0.5, 0.5, 0.62), Vec3::new(0.5, 0.5, 1.0), 60.0);
    for k in [0u32, 1, 2, 5] {
        let sc = scene(
            vec![(
                shell.clone(),
                material(MaterialKind::Lambertian, Vec3::splat(albedo)),
            )],
            vec![Light::Sphere {
                center: Vec3::splat(0.5),
                radius: r,
                radiance: Vec3::splat(radiance),
            }],
            0.0,
            view,
            settings(32, 16, k),
        );
        let film = render(&sc);
        let values: Vec<f32> = film.color().iter().map(grey).collect();
        let (mean, error) = mean_and_error(&values);
        let q = albedo * (1.0 - s);
        let expected = (albedo * radiance * s * (1.0 - q.powi(k as i32)) / (1.0 - q)) as f64;
        println!("max_depth {k}: {mean:.5} ± {error:.5}, expected {expected:.5}");
        // The icosphere's flat faces lie up to 0.05 % inside the sphere the formula assumes.
        assert!(
            (mean - expected).abs() <= 4.0 * error + 2e-3 * expected,
            "max_depth {k}: {mean} ± {error}, expected {expected}"
        );
    }
}

/// A white plastic sphere in a white furnace: whatever the coat does not reflect, the base
/// must return, so every pixel sees the environment's 0.75. The camera frames the inside of
/// the sphere's outline only, from its centre to near grazing.
#[test]
fn white_plastic_in_a_white_furnace_disappears() {
    for (roughness, bound) in [(0.0f32, 0.01f64), (0.1, 0.015), (0.3, 0.015), (0.5, 0.015)] {
        let plastic = Material {
            roughness,
            ..material(MaterialKind::Plastic, Vec3::ONE)
        };
        let sc = scene(
            vec![(Mesh::icosphere(4), plastic)],
            vec![],
            0.75,
            camera(Vec3::new(0.5, 0.5, 2.5), Vec3::splat(0.5), 19.0),
            settings(24, 64, 8),
        );
        let values: Vec<f32> = render(&sc).color().iter().map(grey).collect();
        let (mean, error) = mean_and_error(&values);
        println!("plastic roughness {roughness}: {mean:.5} ± {error:.5}, expected 0.75");
        assert!(
            (mean / 0.75 - 1.0).abs() <= bound + 4.0 * error / 0.75,
            "plastic roughness {roughness}: mean {mean} ± {error}, expected 0.75 within {bound}"
        );
    }
}

/// A non-absorbing glass slab with parallel faces in front of a uniform one-sided quad light,
/// seen at normal incidence: of radiance L the slab transmits L·(1 − R)²·Σ R^(2n) =
/// L·(1 − R)/(1 + R), R the Fresnel reflectance of one face. Every path is a specular chain
/// (front face, any number of internal reflections, back face, light).
#[test]
fn glass_slab_transmits_the_fresnel_series() {
    let (radiance, ior) = (2.0f32, 1.5f32);
    let (lo, hi) = (Vec3::new(-2.0, -2.0, -0.1), Vec3::new(2.0, 2.0, 0.1));
    let mut slab = Mesh::unit_cube();
    for p in &mut slab.positions {
        *p = lo + *p * (hi - lo);
    }
    let glass = Material {
        ior,
        ..material(MaterialKind::Dielectric, Vec3::ONE)
    };
    let sc = scene(
        vec![(slab, glass)],
        vec![Light::Quad {
            corner: Vec3::new(-10.0, -10.0, -1.0),
            edge_u: Vec3::new(20.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 20.0, 0.0),
            radiance: Vec3::splat(radiance),
            two_sided: false,
        }],
        0.0,
        camera(Vec3::new(0.0, 0.0, 3.0), Vec3::ZERO, 4.0),
        settings(32, 256, 16),
    );
    let values: Vec<f32> = render(&sc).color().iter().map(grey).collect();
    let (mean, error) = mean_and_error(&values);
    let f = ((ior - 1.0) / (ior + 1.0)).powi(2);
    let expected = (radiance * (1.0 - f) / (1.0 + f)) as f64;
    println!("glass slab: {mean:.5} ± {error:.5}, expected {expected:.5}");
    assert!(
        (mean - expected).abs() <= 4.0 * error,
        "glass slab transmits {mean} ± {error}, expected {expected}"
    );
}
