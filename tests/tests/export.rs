//! Export of broken objects with their matter (`lazysolid_renderer::export`): the glTF binary
//! read back by the `gltf` crate (a reader written apart from lazysolid) holds a node, mesh,
//! material and image per piece and the explosion as animation; the atlas texels equal the
//! store's colours at the object positions of their centres, on the outer surface and the cut
//! faces; lazysolid's path tracer renders the exported OBJ pieces through their texture
//! coordinates like the scene through its store; and the tools people use accept the file: the
//! Khronos glTF validator reports no error or warning, and Blender imports every piece as a
//! mesh with its image.

use glam::{Vec2, Vec3};
use lazysolid_renderer::diff::flip_images;
use lazysolid_renderer::export::{barycentric, export_broken, ExportOptions, ExportedObject};
use lazysolid_renderer::output::{tonemapped_rgb8, Operator, ToneMap};
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use lazysolid_tests::with_gpu;
use std::path::{Path, PathBuf};

/// Texel density of the test exports: two texels per voxel of the test scene's R = 32 store.
const DENSITY: f32 = 64.0;

/// Largest FLIP mean between the render through the exported atlases and the render through
/// the store (same camera, light, samples and seed). Measured 2026-12-07 on lavapipe: mean
/// 0.0037, p95 0.018; what differs is the filtering (the atlas' MIP footprint against the
/// store's nearest voxel) and the shading at the atlas' seams.
const EXPORT_FLIP_MEAN_LIMIT: f32 = 0.02;

fn fracture_scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/test/fracture.toml")
}

fn tone_map() -> ToneMap {
    ToneMap {
        exposure_ev: 0.0,
        operator: Operator::AcesFitted,
    }
}

/// The test scene's broken bunny exported into `dir`, with its tracer's still (time 0).
fn export_and_render(dir: &Path) -> (Vec<ExportedObject>, image::RgbImage, Vec<Sample>) {
    let scene = Scene::load(&fracture_scene()).unwrap();
    with_gpu(|gpu| {
        let mut tracer = PathTracer::new(gpu, &scene).unwrap();
        let options = ExportOptions {
            texels_per_unit: Some(DENSITY),
            mip_levels: 2,
        };
        let objects = export_broken(&scene, tracer.scene_stores(), dir, &options).unwrap();
        let samples = sample_glb(&objects[0]);
        // The store's colours at the samples, through the tracer's own lookups.
        let stores = tracer.scene_stores();
        let mut checked = samples.clone();
        for piece in 0..objects[0].pieces.len() {
            let at: Vec<usize> = (0..samples.len())
                .filter(|&i| samples[i].piece == piece)
                .collect();
            let slot = stores.slot_of(objects[0].pieces[piece].instance).unwrap();
            let points: Vec<Vec3> = at.iter().map(|&i| samples[i].point).collect();
            let normals: Vec<Vec3> = at.iter().map(|&i| samples[i].normal).collect();
            let colours = stores.albedo_srgb(slot, &points, &normals).unwrap();
            for (&i, c) in at.iter().zip(colours) {
                let c = c.expect("every sample point reads stored matter");
                let b = (c.clamp(Vec3::ZERO, Vec3::ONE) * 255.0).round();
                checked[i].store = [b.x as u8, b.y as u8, b.z as u8];
            }
        }
        let film = tracer.render(|_| {}).unwrap();
        (
            objects,
            tonemapped_rgb8(&film, &tone_map()).unwrap(),
            checked,
        )
    })
}

/// One atlas texel read back from the glTF binary.
#[derive(Clone, Debug)]
struct Sample {
    piece: usize,
    interior: bool,
    /// Object-space position of the texel's centre.
    point: Vec3,
    normal: Vec3,
    /// The texel's colour in the exported image.
    texel: [u8; 3],
    /// The store's colour at `point`, filled in later.
    store: [u8; 3],
}

/// Reads the binary with the `gltf` crate and checks its structure; returns one texel per
/// triangle whose centroid's texel centre lies on it.
fn sample_glb(object: &ExportedObject) -> Vec<Sample> {
    let bytes = std::fs::read(&object.glb).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let blob = gltf.blob.as_deref().expect("a GLB binary chunk");
    let doc = &gltf.document;
    let n = object.pieces.len();
    assert_eq!(doc.nodes().filter(|n| n.mesh().is_some()).count(), n);
    assert_eq!(doc.meshes().count(), n);
    assert_eq!(doc.images().count(), n);
    assert_eq!(doc.default_scene().unwrap().nodes().count(), n);
    let animation = doc.animations().next().expect("the explosion as animation");
    assert_eq!(animation.channels().count(), 3 * n);
    for channel in animation.channels() {
        assert_eq!(channel.sampler().input().count(), object.times);
    }
    let mut samples = Vec::new();
    for (k, node) in doc.default_scene().unwrap().nodes().enumerate() {
        let mesh = node.mesh().unwrap();
        let primitive = mesh.primitives().next().unwrap();
        let material = primitive.material();
        let info = material
            .pbr_metallic_roughness()
            .base_color_texture()
            .expect("the atlas as base colour");
        let gltf::image::Source::View { view, mime_type } = info.texture().source().source() else {
            panic!("piece {k}: the image is not in the binary")
        };
        assert_eq!(mime_type, "image/png");
        let png = &blob[view.offset()..view.offset() + view.length()];
        let image = image::load_from_memory(png).unwrap().to_rgb8();
        let reader = primitive.reader(|_| Some(blob));
        let positions: Vec<Vec3> = reader
            .read_positions()
            .unwrap()
            .map(Vec3::from_array)
            .collect();
        let uvs: Vec<Vec2> = reader
            .read_tex_coords(0)
            .unwrap()
            .into_f32()
            .map(Vec2::from_array)
            .collect();
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        let interior = &object.pieces[k].atlas.interior;
        assert_eq!(indices.len(), 3 * interior.len(), "piece {k}");
        let size = Vec2::new(image.width() as f32, image.height() as f32);
        for (t, tri) in indices.chunks_exact(3).enumerate() {
            let [a, b, c] = [0, 1, 2].map(|j| uvs[tri[j] as usize] * size);
            let [pa, pb, pc] = [0, 1, 2].map(|j| positions[tri[j] as usize]);
            let texel = ((a + b + c) / 3.0).floor();
            let centre = texel + Vec2::splat(0.5);
            let Some(l) = barycentric(centre, a, b, c) else {
                continue;
            };
            if l.min_element() < 0.0 {
                continue;
            }
            let rgb = image.get_pixel(texel.x as u32, texel.y as u32).0;
            samples.push(Sample {
                piece: k,
                interior: interior[t],
                point: pa * l.x + pb * l.y + pc * l.z,
                normal: (pb - pa).cross(pc - pa).normalize_or_zero(),
                texel: rgb,
                store: [0; 3],
            });
        }
    }
    samples
}

/// The atlas is the matter, and the exported pieces render like the scene.
#[test]
fn exported_atlases_hold_the_stores_matter_and_render_like_it() {
    let dir = tempfile::tempdir().unwrap();
    let (objects, still, samples) = export_and_render(dir.path());
    assert_eq!(objects.len(), 1);
    let object = &objects[0];
    assert_eq!(object.name, "bunny");
    assert_eq!(object.pieces.len(), 6);
    assert_eq!(object.times, 4, "the explosion's 4 frames");
    for p in &object.pieces {
        assert!(p.atlas.covered > 0 && p.atlas.holes == 0, "{:?}", p.png);
    }
    let (inside, outside) =
        samples.iter().fold(
            (0, 0),
            |(i, o), s| {
                if s.interior {
                    (i + 1, o)
                } else {
                    (i, o + 1)
                }
            },
        );
    println!("{inside} samples on cut faces, {outside} on the outer surface");
    assert!(inside > 200 && outside > 200, "{inside} / {outside}");
    for s in &samples {
        assert_eq!(s.texel, s.store, "{s:?}");
    }

    // The pieces through their texture coordinates: OBJ in the rest pose's world
    // coordinates, each with its atlas as albedo map, in the same light and camera.
    let text = std::fs::read_to_string(fracture_scene()).unwrap();
    let keep: String = text
        .split("\n[")
        .filter(|section| {
            ["camera]", "render]", "[light]]", "environment]"]
                .iter()
                .any(|s| section.starts_with(s))
        })
        .map(|s| format!("\n[{s}"))
        .collect();
    let mut scene = keep;
    scene += "\n[[mesh]]\nname = \"ground\"\nshape = \"quad\"\n\
              [[material]]\nname = \"grey\"\nkind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]\n\
              [[instance]]\nmesh = \"ground\"\nmaterial = \"grey\"\nscale = 10\ntranslate = [-5, 0, -5]\n";
    for (k, p) in object.pieces.iter().enumerate() {
        scene += &format!(
            "[[mesh]]\nname = \"p{k}\"\npath = \"{}\"\nnormalize = false\n\
             [[material]]\nname = \"m{k}\"\nkind = \"lambertian\"\nalbedo_map = \"{}\"\n\
             [[instance]]\nmesh = \"p{k}\"\nmaterial = \"m{k}\"\n",
            p.obj.display(),
            p.png.display()
        );
    }
    let film = lazysolid_tests::render_scene_text(dir.path(), &scene);
    let exported = tonemapped_rgb8(&film, &tone_map()).unwrap();
    let report = flip_images(&still, &exported).unwrap();
    println!(
        "render through the atlases vs through the store: FLIP mean {:.4}, p95 {:.4}",
        report.mean, report.p95
    );
    if let Some(out) = std::env::var_os("LAZYSOLID_EXPORT_FIGURES") {
        still
            .save(Path::new(&out).join("export_store.png"))
            .unwrap();
        exported
            .save(Path::new(&out).join("export_atlas.png"))
            .unwrap();
    }
    assert!(
        report.mean <= EXPORT_FLIP_MEAN_LIMIT,
        "FLIP mean {} > {EXPORT_FLIP_MEAN_LIMIT}",
        report.mean
    );

    // The tools people use: the Khronos validator finds no error, and Blender imports every
    // piece as a mesh with its image.
    let line = check_with_tools(&object.glb);
    let n = object.pieces.len();
    for (key, want) in [("meshes", n), ("textured_meshes", n), ("images", n)] {
        assert!(
            line.contains(&format!("\"{key}\": {want},")),
            "{key}: {line}"
        );
    }
    assert!(!line.contains("\"animations\": 0,"), "{line}");
}

/// A scan whose surface intersects itself (the cow, 12 pieces, seed 1: one piece had an edge of
/// four triangles, now separated) exports pieces that the validator and Blender accept, with
/// matter on every covered texel.
#[test]
fn a_self_intersecting_scan_exports_pieces_the_tools_accept() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("cow.toml");
    std::fs::write(
        &scene,
        format!(
            "[camera]\nposition = [-2.0, 1.2, 2.0]\nlook_at = [0.5, 0.4, 0.5]\nfov_y = 40\n\
             [render]\nwidth = 8\nheight = 8\nspp = 1\n\
             [[mesh]]\nname = \"cow\"\npath = \"{}\"\n\
             [[material]]\nname = \"m\"\nkind = \"lambertian\"\n\
             texture = {{ kind = \"synthesized\", exemplar = \"leather\", seed = 1, resolution = 16, store = \"perfect_hash\" }}\n\
             [[instance]]\nname = \"cow\"\nmesh = \"cow\"\nmaterial = \"m\"\n\
             [[fracture]]\ninstance = \"cow\"\npieces = 12\nseed = 1\n\
             [environment]\nradiance = [0.5, 0.5, 0.5]\n",
            repo("assets/meshes/cow.off").display()
        ),
    )
    .unwrap();
    let scene = Scene::load(&scene).unwrap();
    let objects = with_gpu(|gpu| {
        let tracer = PathTracer::new(gpu, &scene).unwrap();
        let options = ExportOptions {
            texels_per_unit: Some(32.0),
            mip_levels: 1,
        };
        export_broken(&scene, tracer.scene_stores(), dir.path(), &options).unwrap()
    });
    let cow = &objects[0];
    assert_eq!(
        (cow.name.as_str(), cow.pieces.len(), cow.times),
        ("cow", 12, 1)
    );
    for p in &cow.pieces {
        assert!(p.atlas.covered > 0 && p.atlas.holes == 0, "{:?}", p.png);
    }
    let line = check_with_tools(&cow.glb);
    assert!(
        line.contains("\"meshes\": 12, \"textured_meshes\": 12, \"images\": 12,"),
        "{line}"
    );
}

/// Runs the Khronos validator on `glb` (which must report no error or warning) and imports it
/// into Blender; returns Blender's report line.
fn check_with_tools(glb: &Path) -> String {
    let validator = run(std::process::Command::new("bash")
        .arg(repo("scripts/gltf-validate.sh"))
        .arg(glb));
    println!("{validator}");
    assert!(validator.contains(" 0 errors, 0 warnings"), "{validator}");
    let blender = run(std::process::Command::new("blender")
        .args(["-b", "--factory-startup", "--python"])
        .arg(repo("scripts/blender-import.py"))
        .arg("--")
        .arg(glb));
    let line = blender
        .lines()
        .find_map(|l| l.strip_prefix("LAZYSOLID_BLENDER "))
        .unwrap_or_else(|| panic!("no report from Blender:\n{blender}"));
    println!("Blender: {line}");
    line.to_string()
}

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

/// Runs a checker and returns its output; a missing program or a failed run fails the test
/// with how to install it.
fn run(command: &mut std::process::Command) -> String {
    let out = command.output().unwrap_or_else(|e| {
        panic!("{command:?}: {e} (bash scripts/install-deps.sh --tests installs blender, node and the validator)")
    });
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{command:?} failed:\n{text}");
    text
}
