//! Texture coordinates from mesh files to the path tracer: OBJ `vt` kept through the loader and
//! the BVH, MikkTSpace tangents, the image lookup (GPU against its CPU twin, through the MIP
//! pyramid and through compressed trees), albedo images the
//! right way up, and normal maps bending the shading normal along the mesh's tangent frame.

use glam::{Vec2, Vec3, Vec4};
use lazysolid_compute::ctree::colour::ColourTrees;
use lazysolid_compute::ctree::CtreeOptions;
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::accel::{corner_normals, corner_tangents};
use lazysolid_renderer::glint::NormalExample;
use lazysolid_renderer::image_texture::{sample, ImageSet, ImageTexture};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_renderer::output::Film;
use lazysolid_renderer::scene::Scene;
use lazysolid_tests::kernels::render_test::IMAGE_TEST;
use lazysolid_tests::{render_scene_text, with_gpu, ImageTestPush};
use rand::{Rng, SeedableRng};
use std::path::Path;
use std::sync::Arc;

/// A unit quad in the xy-plane facing +z whose texture coordinates run (u, v) = (x, y).
const QUAD_OBJ: &str = "\
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3
f 1/1 3/3 4/4
";

fn write(dir: &Path, name: &str, text: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn obj_texture_coordinates_and_mikktspace_tangents_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = Mesh::load(write(dir.path(), "quad.obj", QUAD_OBJ)).unwrap();
    let uvs = mesh.uvs.as_ref().expect("the file has vt");
    for (p, uv) in mesh.positions.iter().zip(uvs) {
        assert_eq!(Vec2::new(p.x, p.y), *uv);
    }
    // u grows along +x, v along +y, the normal is +z: tangent +x, bitangent +y = +z × +x.
    let normals = corner_normals(&mesh, 50.0);
    let tangents = corner_tangents(&mesh, &normals).unwrap();
    for (t, n) in tangents.iter().flatten().zip(normals.iter().flatten()) {
        assert!((t.truncate() - Vec3::X).length() < 1e-5, "{t}");
        assert!((n.cross(t.truncate()) * t.w - Vec3::Y).length() < 1e-5);
    }

    // A seam: the same corner with two coordinates stays two vertices.
    let seam = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n\
                f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n";
    let mesh = Mesh::load(write(dir.path(), "seam.obj", seam)).unwrap();
    assert_eq!(mesh.positions.len(), 5);
    assert_eq!(mesh.uvs.as_ref().unwrap().len(), 5);

    // Meshes without coordinates keep working, with none.
    let plain = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
    assert!(Mesh::load(write(dir.path(), "plain.obj", plain))
        .unwrap()
        .uvs
        .is_none());

    // Coordinates on some groups only: refused, naming the file and the group.
    let partial = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
                   g textured\nf 1/1 2/2 3/3\ng bare\nf 1 3 4\n";
    let err = Mesh::load(write(dir.path(), "partial.obj", partial))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("partial.obj") && err.contains("bare") && err.contains("vt"),
        "{err}"
    );
}

/// `width`×`height` random sRGB texels with alpha, written as a PNG.
fn random_png(path: &Path, width: u32, height: u32, seed: u64) {
    let mut r = rand_pcg::Pcg64::seed_from_u64(seed);
    let img = image::RgbaImage::from_fn(width, height, |_, _| {
        image::Rgba([r.random(), r.random(), r.random(), r.random()])
    });
    img.save(path).unwrap();
}

fn random_normals(size: usize, seed: u64) -> NormalExample {
    let mut r = rand_pcg::Pcg64::seed_from_u64(seed);
    let texels = (0..size * size)
        .map(|_| {
            let a: f32 = r.random_range(0.0..std::f32::consts::TAU);
            let s: f32 = r.random_range(0.0..0.9);
            Vec2::new(a.cos(), a.sin()) * s
        })
        .collect();
    NormalExample::from_normals("random normals", size, texels).unwrap()
}

#[test]
fn the_image_lookup_on_the_device_matches_its_cpu_twin() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("odd.png");
    random_png(&png, 37, 23, 5);
    let images = [
        ImageTexture::load_color(&png).unwrap(),
        ImageTexture::from_normals("normals", &random_normals(32, 6)),
    ];
    let mut set = ImageSet::default();
    for image in &images {
        set.add(image).unwrap();
    }
    // The colour image again, read through its compressed trees.
    let rgb: Vec<u8> = images[0].levels[0]
        .iter()
        .flat_map(|&t| [t as u8, (t >> 8) as u8, (t >> 16) as u8])
        .collect();
    let options = CtreeOptions {
        step: 2.0,
        ..Default::default()
    };
    let trees = Arc::new(ColourTrees::build("odd.png", &rgb, 37, 23, &options).unwrap());
    let coded = set.add_ctree(&images[0], &trees);
    let mut r = rand_pcg::Pcg64::seed_from_u64(7);
    let queries: Vec<[Vec2; 3]> = (0..2000)
        .map(|i| {
            let uv = Vec2::new(r.random_range(-2.0..3.0), r.random_range(-2.0..3.0));
            // Footprints from a hundredth of a texel to the whole image, some very thin.
            let scale = 10f32.powf(r.random_range(-3.5..0.5));
            let angle: f32 = r.random_range(0.0..std::f32::consts::TAU);
            let thin = if i % 3 == 0 {
                r.random_range(0.01..1.0)
            } else {
                1.0
            };
            let a = Vec2::new(angle.cos(), angle.sin()) * scale;
            let b = Vec2::new(-angle.sin(), angle.cos()) * scale * thin;
            [uv, a, b]
        })
        .collect();
    with_gpu(|gpu| {
        let device = set.upload(gpu).unwrap();
        let kernel = gpu.kernel(&IMAGE_TEST).unwrap();
        let flat: Vec<[f32; 2]> = queries.iter().flatten().map(|v| v.to_array()).collect();
        let input = GpuBuffer::from_slice(gpu, "image queries", &flat).unwrap();
        for (index, image) in images.iter().chain([&images[0]]).enumerate() {
            let output = GpuBuffer::<[f32; 4]>::new(gpu, "image results", queries.len()).unwrap();
            let push = ImageTestPush {
                queries: input.address(),
                results: output.address(),
                image: index as u32,
                n: queries.len() as u32,
            };
            gpu.submit(|rec| {
                rec.dispatch(
                    &kernel,
                    kernel.groups_for(queries.len() as u64),
                    &device.bindings(),
                    &push,
                )
            })
            .unwrap();
            let got = output.read().unwrap();
            let mut worst = 0.0f32;
            for (q, g) in queries.iter().zip(&got) {
                let want = if index as u32 == coded {
                    sample::lookup_ctree(image, &trees, q[0], q[1], q[2])
                } else {
                    sample::lookup(image, q[0], q[1], q[2])
                };
                let err = (Vec4::from_array(*g) - want).abs().max_element();
                worst = worst.max(err);
            }
            // f32 coordinates and exp/log differ in the last bits between the compilers; a
            // wrong texel, level or tap count errs by far more (texels are random).
            assert!(worst < 2e-3, "{}: worst difference {worst}", image.name);
        }
    });
}

/// The built-in quad seen from straight above, filling the frame, with −z up in the picture:
/// the quad's texture coordinates put the image's top row there.
fn quad_scene(material: &str) -> String {
    quad_scene_sized(material, 32, 16)
}

/// [`quad_scene`] at `side`² pixels and `spp` samples per pixel.
pub(crate) fn quad_scene_sized(material: &str, side: u32, spp: u32) -> String {
    format!(
        r#"
[camera]
position = [0.5, 4.0, 0.5]
look_at = [0.5, 0.0, 0.5]
up = [0.0, 0.0, -1.0]
fov_y = 14.0

[render]
width = {side}
height = {side}
spp = {spp}
max_depth = 1

[[mesh]]
name = "quad"
shape = "quad"

[[material]]
name = "m"
{material}

[[instance]]
mesh = "quad"
material = "m"

[environment]
radiance = [1.0, 1.0, 1.0]
"#
    )
}

#[test]
fn a_textured_quad_shows_its_image_the_right_way_up() {
    let dir = tempfile::tempdir().unwrap();
    // Top-left red, top-right green, bottom-left blue, bottom-right white.
    let colours = [[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255]];
    let img = image::RgbImage::from_fn(2, 2, |x, y| image::Rgb(colours[(y * 2 + x) as usize]));
    img.save(dir.path().join("quadrants.png")).unwrap();
    let film = render_scene_text(
        dir.path(),
        &quad_scene("kind = \"lambertian\"\nalbedo_map = \"quadrants.png\""),
    );
    let at = |x: usize, y: usize| Vec3::from_array(film.color()[y * 32 + x]);
    // Under a white sky of radiance 1 a Lambertian plane's radiance is its albedo.
    let quadrant_centres = [(8, 8), (24, 8), (8, 24), (24, 24)];
    for ((x, y), c) in quadrant_centres.into_iter().zip(colours) {
        let want = Vec3::from_array(c.map(|v| v as f32 / 255.0));
        let got = at(x, y);
        assert!(
            (got - want).abs().max_element() < 0.1,
            "pixel ({x}, {y}): {got}, want {want}"
        );
    }
}

/// A constant tangent-space normal (x, y) as a 16² normal map PNG.
fn constant_normal_png(path: &Path, n: Vec2) {
    let b = |v: f32| ((v * 0.5 + 0.5) * 255.0).round() as u8;
    let z = (1.0 - n.length_squared()).sqrt();
    let img = image::RgbImage::from_pixel(16, 16, image::Rgb([b(n.x), b(n.y), b(z)]));
    img.save(path).unwrap();
}

#[test]
fn a_normal_map_bends_the_shading_normal_along_the_mesh_tangent_frame() {
    let dir = tempfile::tempdir().unwrap();
    // The quad's u runs along +x and v along −z (its image's top row at z = 0); its normal is +y.
    let s = 0.5f32;
    let c = (1.0 - s * s).sqrt();
    let cases = [
        (Vec2::new(0.0, 0.0), Vec3::Y),
        (Vec2::new(s, 0.0), Vec3::new(s, c, 0.0)),
        (Vec2::new(0.0, s), Vec3::new(0.0, c, -s)),
    ];
    for (k, (n, want)) in cases.into_iter().enumerate() {
        let name = format!("normal{k}.png");
        constant_normal_png(&dir.path().join(&name), n);
        let film = render_scene_text(
            dir.path(),
            &quad_scene(&format!(
                "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\nnormal_map = \"{name}\""
            )),
        );
        let normals = film.normal().expect("the first pass writes normals");
        let got = Vec3::from_array(normals[16 * 32 + 16]);
        // 8-bit texels: 0 is stored as 128/255 · 2 − 1 = 0.004.
        assert!(
            (got - want).length() < 0.01,
            "map {n}: normal {got}, want {want}"
        );
    }
}

#[test]
fn materials_that_read_texture_coordinates_need_meshes_that_have_them() {
    let dir = tempfile::tempdir().unwrap();
    constant_normal_png(&dir.path().join("n.png"), Vec2::ZERO);
    let text = quad_scene("kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\nnormal_map = \"n.png\"")
        .replace("shape = \"quad\"", "shape = \"cube\"");
    let path = write(dir.path(), "scene.toml", &text);
    let err = Scene::load(&path).unwrap_err().to_string();
    assert!(
        err.contains("texture coordinates") && err.contains("\"quad\""),
        "{err}"
    );

    // A normal map under the smallest edge: the file, the field and the limit.
    image::RgbImage::new(4, 6)
        .save(dir.path().join("bad.png"))
        .unwrap();
    let text =
        quad_scene("kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\nnormal_map = \"bad.png\"");
    let err = Scene::load(&write(dir.path(), "scene.toml", &text))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("bad.png") && err.contains("normal_map") && err.contains("4x6"),
        "{err}"
    );

    // vMF lobes out of range, lobes with another filter, a filter without a map.
    for (keys, needles) in [
        (
            "normal_map = \"n.png\"\nvmf_lobes = 9",
            &["vmf_lobes", "1..=8"][..],
        ),
        (
            "normal_map = \"n.png\"\nnormal_filter = \"mip\"\nvmf_lobes = 4",
            &["vmf_lobes", "applies only"][..],
        ),
        (
            "normal_filter = \"vmf\"",
            &["normal_filter", "normal_map"][..],
        ),
        (
            "normal_map = \"n.png\"\nnormal_filter = \"fancy\"",
            &["fancy"][..],
        ),
    ] {
        let text = quad_scene(&format!(
            "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\n{keys}"
        ));
        let err = Scene::load(&write(dir.path(), "scene.toml", &text))
            .unwrap_err()
            .to_string();
        for n in needles {
            assert!(err.contains(n), "{keys}: {err}");
        }
    }

    // An albedo map beside a colour.
    let text = quad_scene("kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\nalbedo_map = \"n.png\"");
    let err = Scene::load(&write(dir.path(), "scene.toml", &text))
        .unwrap_err()
        .to_string();
    assert!(err.contains("albedo_map") || err.contains("color"), "{err}");
}

/// A glint material reading the mesh's texture coordinates: on a quad whose coordinates are
/// its object x and z, seen from straight above (round footprints), it renders as the planar
/// projection of the same microstructure does.
#[test]
fn a_glint_on_mesh_coordinates_matches_the_planar_projection_where_they_agree() {
    let dir = tempfile::tempdir().unwrap();
    let quad = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt -1 -1\nvt 1 -1\nvt 1 1\nvt -1 1\n\
                f 1/1 3/3 2/2\nf 1/1 4/4 3/3\n";
    write(dir.path(), "xz.obj", quad);
    let scratches =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/glints/scratches.png");
    let scene = |uv: &str| {
        format!(
            r#"
[camera]
position = [0.0, 3.0, 0.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 0.0, -1.0]
fov_y = 30.0

[render]
width = 48
height = 48
spp = 16
max_depth = 1

[[mesh]]
name = "quad"
path = "xz.obj"
normalize = false

[[material]]
name = "m"
kind = "glint"
preset = "aluminium"
height_map = "{}"
height_scale = 0.6
intrinsic_roughness = 0.02
scale = 4.0
uv = "{uv}"

[[instance]]
mesh = "quad"
material = "m"

[[light]]
kind = "quad"
corner = [-0.5, 4.0, -0.5]
edge_u = [1.0, 0.0, 0.0]
edge_v = [0.0, 0.0, 1.0]
radiance = [20.0, 20.0, 20.0]
"#,
            scratches.display()
        )
    };
    let planar = render_scene_text(dir.path(), &scene("planar"));
    let mesh = render_scene_text(dir.path(), &scene("mesh"));
    let srgb =
        |f: &Film| lazysolid_renderer::output::tonemapped_rgb8(f, &Default::default()).unwrap();
    let flip = lazysolid_renderer::diff::flip_images(&srgb(&planar), &srgb(&mesh))
        .unwrap()
        .mean;
    let level: f32 = planar
        .color()
        .iter()
        .map(|c| c[0] + c[1] + c[2])
        .sum::<f32>();
    println!("glint, mesh coordinates against planar: mean FLIP {flip:.4}, planar sum {level:.1}");
    assert!(level > 1.0, "the glints are lit");
    // 64 texels per unit, about 1.5 texels per pixel: the footprints (σ_P about a texel, inside
    // the clamp) differ in form only, the pixel cone's circle against the differentials'
    // near-circle, so the pictures agree closely but not exactly.
    assert!(flip > 0.0 && flip < 0.05, "mean FLIP {flip}");
}
