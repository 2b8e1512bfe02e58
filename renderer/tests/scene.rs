//! The TOML scene loader: the example scenes, every class of error (with file, line and field),
//! instance transforms and the built-in shapes.

use glam::{Vec3, Vec3A};
use lazysolid_renderer::mesh::{Mesh, MAX_ICOSPHERE_SUBDIVISIONS};
use lazysolid_renderer::scene::{
    Environment, Lens, Light, MaterialKind, Scene, SceneError, SolidTextureKind,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn example(name: &str) -> Scene {
    let path = repo().join("scenes").join(name);
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Mesh, material, instance and light counts.
fn counts(s: &Scene) -> [usize; 4] {
    [
        s.meshes.len(),
        s.materials.len(),
        s.instances.len(),
        s.lights.len(),
    ]
}

#[test]
fn default_scene_loads() {
    let s = example("default.toml");
    assert_eq!(counts(&s), [2, 2, 2, 1]);
    assert_eq!(
        (s.render.width, s.render.height, s.render.spp),
        (640, 480, 64)
    );
    assert_eq!(
        (s.render.max_depth, s.render.rr_depth, s.render.seed),
        (8, 3, 0)
    );
    assert_eq!(s.camera.lens, Lens::Pinhole);
    assert_eq!(s.camera.up, Vec3::Y);
    let armadillo = &s.meshes[0].mesh;
    assert_eq!(
        (armadillo.positions.len(), armadillo.triangles.len()),
        (26_002, 52_000)
    );
    // Normalized: the longest axis spans [0, 1].
    let b = armadillo.bounds();
    assert!((b.size().max_element() - 1.0).abs() < 1e-5, "{b:?}");
    assert!(b.min.min_element() >= -1e-6, "{b:?}");
    let marble = &s.materials[0];
    assert_eq!(marble.kind, MaterialKind::Plastic);
    assert_eq!(marble.roughness, 0.3);
    assert_eq!(marble.ior, 1.5);
    assert_eq!(
        marble.texture.as_ref().map(|t| t.kind),
        Some(SolidTextureKind::Marble)
    );
    assert_eq!(
        s.materials[1].texture.as_ref().map(|t| t.kind),
        Some(SolidTextureKind::Checker)
    );
    assert!(matches!(s.lights[0], Light::Sphere { radius, .. } if radius == 0.8));
    assert!(matches!(s.environment, Environment::Constant(c) if c.z > c.x && c.x > 0.0));
    // The armadillo (scale 2) stands on the floor, centred in x.
    let inst = &s.instances[0];
    assert_eq!((inst.mesh, inst.material), (0, 0));
    let world_min = inst.transform.transform_point3(b.min);
    let world_max = inst.transform.transform_point3(b.max);
    assert!(world_min.y.abs() < 1e-5, "{world_min}");
    assert!(
        (world_min.x + world_max.x).abs() < 1e-4,
        "{world_min} {world_max}"
    );
}

#[test]
fn test_scenes_load() {
    let s = example("test/textured.toml");
    assert_eq!(counts(&s), [2, 2, 2, 1]);
    assert_eq!(
        (
            s.render.width,
            s.render.height,
            s.render.spp,
            s.render.max_depth
        ),
        (96, 72, 16, 4)
    );
    assert_eq!(s.meshes[0].mesh.triangles.len(), 75_408);
    assert_eq!(
        s.materials[0].texture.as_ref().map(|t| t.kind),
        Some(SolidTextureKind::Wood)
    );
    assert_eq!(s.materials[0].kind, MaterialKind::Lambertian);

    let s = example("test/glass_metal.toml");
    assert_eq!(counts(&s), [2, 3, 3, 1]);
    assert_eq!((s.render.spp, s.render.max_depth), (16, 8));
    assert_eq!(s.meshes[0].mesh.triangles.len(), 20 * 4usize.pow(4));
    let gold = &s.materials[0];
    assert_eq!(gold.kind, MaterialKind::Conductor);
    // Gold reflects red more than blue: small η and large κ in red.
    assert!(
        gold.color.x < gold.color.z && gold.k.x > gold.k.z,
        "{gold:?}"
    );
    let glass = &s.materials[1];
    assert_eq!(
        (glass.kind, glass.ior, glass.roughness, glass.color),
        (MaterialKind::Dielectric, 1.5, 0.0, Vec3::ONE)
    );
    match s.lights[0] {
        Light::Quad {
            edge_u,
            edge_v,
            two_sided,
            ..
        } => {
            assert!(edge_u.cross(edge_v).y < 0.0, "the light faces down");
            assert!(!two_sided);
        }
        other => panic!("{other:?}"),
    }

    let s = example("test/interior.toml");
    assert_eq!(counts(&s), [3, 3, 7, 1]);
    assert_eq!((s.render.spp, s.render.max_depth), (32, 6));
    assert_eq!(s.environment, Environment::Constant(Vec3::ZERO));
    assert_eq!(s.meshes[1].mesh.triangles.len(), 12);
}

/// Every render scene the repository ships loads (the multiscale folder holds exemplar graphs,
/// not render scenes), and the normal-map scenes carry their maps, filters and UVs.
#[test]
fn every_shipped_scene_loads() {
    let mut loaded = 0;
    for folder in ["", "test", "normal-maps"] {
        let dir = repo().join("scenes").join(folder);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        files.sort();
        for file in files {
            Scene::load(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            loaded += 1;
        }
    }
    assert!(loaded >= 15, "{loaded} scenes");
    for name in ["receding-plane", "v-groove", "sphere"] {
        let s = example(&format!("normal-maps/{name}.toml"));
        let m = s.materials[0].normal_map.as_ref().expect("a normal map");
        assert_eq!(
            m.filter,
            lazysolid_renderer::scene::NormalFilter::Vmf,
            "{name}"
        );
        assert_eq!(m.lobes, 4);
        assert!(s.meshes[0].mesh.uvs.is_some(), "{name}: the mesh has UVs");
    }
}

/// Every wall of the interior faces the inside of the room [-1, 1] × [0, 2] × [-1, 1] and lies
/// on its side of it.
#[test]
fn interior_walls_close_the_room_and_face_inwards() {
    let s = example("test/interior.toml");
    let quad = Mesh::unit_quad();
    let centre = Vec3::new(0.0, 1.0, 0.0);
    for (i, inst) in s.instances.iter().take(5).enumerate() {
        assert_eq!(inst.mesh, 0);
        let p: Vec<Vec3> = quad
            .positions
            .iter()
            .map(|&p| inst.transform.transform_point3(p))
            .collect();
        let normal = (p[2] - p[0]).cross(p[1] - p[0]).normalize();
        let mid = (p[0] + p[2]) * 0.5;
        assert!(
            ((mid - centre).abs().max_element() - 1.0).abs() < 1e-5,
            "wall {i} mid {mid}"
        );
        for q in &p {
            assert!(
                (*q - centre).abs().max_element() < 1.0 + 1e-5,
                "wall {i} corner {q}"
            );
        }
        assert!(((p[1] - p[0]).cross(p[3] - p[0]).length() - 4.0).abs() < 1e-4);
        assert!(
            normal.dot(centre - mid) > 0.999,
            "wall {i} normal {normal} at {mid}"
        );
    }
}

#[test]
fn instance_transform_is_translate_rotate_x_then_y_then_z_scale() {
    let text = BASE.replace(
        "material = \"white\"\n",
        "material = \"white\"\nrotate = [90, 90, 0]\nscale = 2\ntranslate = [10, 20, 30]\n",
    );
    let s = parse(&text).unwrap();
    let t = s.instances[0].transform;
    // x first: (0, 1, 0) → (0, 0, 1) about x, then → (1, 0, 0) about y.
    let p = t.transform_point3(Vec3::Y);
    assert!((p - Vec3::new(12.0, 20.0, 30.0)).length() < 1e-5, "{p}");
    let v = t.transform_vector3(Vec3::Z);
    // (0, 0, 1) → (0, -1, 0) about x, unchanged about y, doubled.
    assert!((v - Vec3::new(0.0, -2.0, 0.0)).length() < 1e-5, "{v}");
}

#[test]
fn thin_lens_and_presets() {
    let text = BASE
        .replace(
            "fov_y = 40\n",
            "fov_y = 40\naperture_radius = 0.05\nfocus_distance = 4.5\n",
        )
        .replace(
            "kind = \"lambertian\"\ncolor = [0.5, 0.5, 0.5]",
            "kind = \"conductor\"\npreset = \"copper\"\nroughness = 0.1",
        );
    let s = parse(&text).unwrap();
    assert_eq!(
        s.camera.lens,
        Lens::ThinLens {
            aperture_radius: 0.05,
            focus_distance: 4.5
        }
    );
    let m = &s.materials[0];
    assert_eq!((m.kind, m.roughness), (MaterialKind::Conductor, 0.1));
    // Copper: reddish (κ and reflectance highest in red).
    assert!(m.k.x > m.k.y && m.k.y > m.k.z, "{m:?}");
}

/// A minimal valid scene; the line numbers of its keys are what the error tests expect.
const BASE: &str = r#"[camera]
position = [0, 1, 5]
look_at = [0, 0.5, 0]
fov_y = 40
[render]
width = 64
height = 48
spp = 4
[[mesh]]
name = "box"
shape = "cube"
[[material]]
name = "white"
kind = "lambertian"
color = [0.5, 0.5, 0.5]
[[instance]]
mesh = "box"
material = "white"
"#;

const FILE: &str = "scenes/t.toml";

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Path::new(FILE))
}

/// The error message of a scene that must fail.
fn error(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Checks that `text` fails with a message containing `FILE:line: expected`.
fn expect(text: &str, line: usize, expected: &str) {
    let e = error(text);
    let want = format!("{FILE}:{line}: {expected}");
    assert!(
        e.contains(&want),
        "expected {want:?}\n got {e:?}\nfor\n{text}"
    );
}

/// BASE with one line replaced (1-based) by `with` (which may span several lines).
fn edit(line: usize, with: &str) -> String {
    let mut lines: Vec<&str> = BASE.lines().collect();
    lines[line - 1] = with;
    lines.join("\n") + "\n"
}

/// BASE followed by `more` (its first line is line 19).
fn append(more: &str) -> String {
    format!("{BASE}{more}")
}

#[test]
fn base_scene_is_valid() {
    let s = parse(BASE).unwrap();
    assert_eq!(counts(&s), [1, 1, 1, 0]);
    assert_eq!(s.environment, Environment::Constant(Vec3::ZERO));
}

#[test]
fn toml_syntax_errors_name_the_line() {
    expect(&edit(4, "fov_y = = 40"), 4, "TOML syntax error");
    expect(&edit(10, "name = \"box"), 10, "TOML syntax error");
    expect(
        &append("[camera]\nfov_y = 3\n"),
        19,
        "TOML syntax error: duplicate key (at `camera`)",
    );
}

#[test]
fn unknown_keys_and_wrong_types_name_the_field() {
    expect(
        &edit(4, "fov_y = 40\nfov = 3"),
        5,
        "camera.fov: unknown field `fov`",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\niorr = 1.5\n"),
        22,
        "material \"glass\".iorr: unknown field `iorr`",
    );
    expect(
        &append("[sky]\nradiance = 1\n"),
        19,
        "sky: unknown field `sky`",
    );
    expect(
        &edit(6, "width = \"64\""),
        6,
        "render.width: invalid type: string \"64\", expected u32",
    );
    expect(
        &edit(6, "width = -64"),
        6,
        "render.width: invalid value: integer `-64`",
    );
    expect(
        &edit(2, "position = [0, 1]"),
        2,
        "camera.position: invalid length 2",
    );
    expect(
        &edit(2, "position = [0, \"1\", 5]"),
        2,
        "camera.position[1]: invalid type: string \"1\", expected f32",
    );
    expect(
        &edit(14, "kind = \"glas\""),
        14,
        "material \"white\".kind: unknown variant `glas`",
    );
    expect(
        &append("[[light]]\nkind = \"point\"\n"),
        20,
        "light #1.kind: unknown variant `point`",
    );
    expect(
        &append("[[instance]]\nmesh = \"box\"\nmaterial = \"white\"\nscale = [1, 2, 1]\n"),
        22,
        "instance #2.scale: invalid type: sequence, expected f32",
    );
}

#[test]
fn missing_required_fields_name_the_table() {
    expect(&edit(8, ""), 5, "render: missing field `spp`");
    let no_camera = BASE.replacen("[camera]", "[kamera]", 1);
    expect(&no_camera, 1, "kamera: unknown field `kamera`");
    let no_camera: String = BASE.lines().skip(4).map(|l| format!("{l}\n")).collect();
    expect(&no_camera, 1, "scene: missing field `camera`");
    expect(&edit(10, ""), 9, "mesh #1: missing field `name`");
    expect(
        &edit(11, ""),
        9,
        "mesh \"box\": needs path = \"file.obj|off\" or shape",
    );
    expect(
        &edit(15, ""),
        12,
        "material \"white\".color: missing (a lambertian material needs color, texture or albedo_map)",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\n"),
        19,
        "material \"glass\".ior: missing (a dielectric needs it, in (1, 4])",
    );
    expect(
        &append("[[material]]\nname = \"metal\"\nkind = \"conductor\"\nroughness = 0.2\n"),
        19,
        "material \"metal\".color: missing (a conductor needs preset, or color (η) and k (κ))",
    );
    expect(
        &append("[[material]]\nname = \"shiny\"\nkind = \"plastic\"\ncolor = [0.5, 0.5, 0.5]\n"),
        19,
        "material \"shiny\".roughness: missing (a plastic material needs it, in [0, 1])",
    );
    expect(
        &append("[[material]]\nname = \"lamp\"\nkind = \"emissive\"\n"),
        19,
        "material \"lamp\".emission: missing (an emissive material needs it)",
    );
    expect(
        &append("[[light]]\nkind = \"sphere\"\nradiance = [1, 1, 1]\nradius = 1\n"),
        19,
        "light #1.center: missing (a sphere light needs center, radius and radiance)",
    );
    expect(
        &append("[[light]]\nkind = \"quad\"\nradiance = [1, 1, 1]\ncorner = [0, 2, 0]\nedge_u = [1, 0, 0]\n"),
        19,
        "light #1.edge_v: missing (a quad light needs corner, edge_u, edge_v and radiance)",
    );
    expect(
        &edit(4, "fov_y = 40\naperture_radius = 0.1"),
        5,
        "camera.focus_distance: missing: a thin lens needs both",
    );
    expect(
        &append("[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"wood\", color_a = [1, 1, 1] }\n"),
        22,
        "material \"m\".texture.color_b: missing (a marble, wood or checker texture blends two colours)",
    );
    expect(
        &append("[environment]\n"),
        19,
        "environment: needs radiance = [r, g, b] or path",
    );
}

#[test]
fn fields_of_another_kind_name_the_kinds_that_accept_them() {
    expect(
        &edit(15, "color = [0.5, 0.5, 0.5]\nior = 1.5"),
        16,
        "material \"white\".ior: does not apply to a lambertian material (accepted by: plastic, dielectric)",
    );
    expect(
        &append("[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 1.5\ntexture = { kind = \"wood\", color_a = [1, 1, 1], color_b = [0, 0, 0] }\n"),
        23,
        "material \"glass\".texture: does not apply to a dielectric material (accepted by: lambertian, plastic)",
    );
    expect(
        &append("[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nemission = [1, 1, 1]\nroughness = 0.5\n"),
        23,
        "material \"lamp\".roughness: does not apply to an emissive material",
    );
    expect(
        &append("[[material]]\nname = \"gold\"\nkind = \"conductor\"\npreset = \"gold\"\nroughness = 0.2\nk = [1, 1, 1]\n"),
        24,
        "material \"gold\".k: a preset gives both η and κ",
    );
    expect(
        &append("[[material]]\nname = \"m\"\nkind = \"plastic\"\nroughness = 0.2\ncolor = [1, 1, 1]\ntexture = { kind = \"wood\", color_a = [1, 1, 1], color_b = [0, 0, 0] }\n"),
        24,
        "material \"m\".texture: color and texture are exclusive",
    );
    expect(
        &append("[[light]]\nkind = \"sphere\"\nradiance = [1, 1, 1]\ncenter = [0, 2, 0]\nradius = 1\ntwo_sided = true\n"),
        24,
        "light #1.two_sided: only quad lights have it",
    );
    expect(
        &edit(11, "shape = \"cube\"\nsubdivisions = 2"),
        12,
        "mesh \"box\".subdivisions: only shape = \"sphere\" has it",
    );
    expect(
        &edit(11, "shape = \"cube\"\nnormalize = false"),
        12,
        "mesh \"box\".normalize: only mesh files have it",
    );
    expect(
        &edit(11, "shape = \"cube\"\npath = \"cube.off\""),
        11,
        "mesh \"box\".shape: path and shape are exclusive",
    );
    expect(
        &append("[environment]\nradiance = [1, 1, 1]\nintensity = 2\n"),
        21,
        "environment.intensity: only a map (path) has it",
    );
    expect(
        &append("[environment]\nradiance = [1, 1, 1]\npath = \"sky.exr\"\n"),
        21,
        "environment.path: radiance and path are exclusive",
    );
}

#[test]
fn out_of_range_values_state_the_limit() {
    let cases: &[(usize, &str, &str)] = &[
        (6, "width = 0", "render.width: 0 is out of range (must be in 1..=8192)"),
        (7, "height = 8193", "render.height: 8193 is out of range (must be in 1..=8192)"),
        (8, "spp = 0", "render.spp: 0 is out of range (must be in 1..=1048576)"),
        (8, "spp = 1048577", "render.spp: 1048577 is out of range"),
        (8, "spp = 4\nmax_depth = 65", "render.max_depth: 65 is out of range (must be in 0..=64)"),
        (8, "spp = 4\nrr_depth = 65", "render.rr_depth: 65 is out of range (must be in 0..=64)"),
        (4, "fov_y = 180", "camera.fov_y: 180 is out of range (must be in (0, 180) degrees)"),
        (4, "fov_y = 0", "camera.fov_y: 0 is out of range"),
        (4, "fov_y = nan", "camera.fov_y: NaN is not finite"),
        (4, "fov_y = inf", "camera.fov_y: inf is not finite"),
        (2, "position = [0, inf, 5]", "camera.position: [0.0, inf, 5.0] has a non-finite component"),
        (
            15,
            "color = [0.5, 1.2, 0.5]",
            "material \"white\".color: channel 1 of [0.5, 1.2, 0.5] is 1.2, out of range (must be in [0, 1]",
        ),
        (15, "color = [-0.1, 0.5, 0.5]", "material \"white\".color: channel 0 of [-0.1, 0.5, 0.5] is -0.1"),
        (15, "color = [0.5, 0.5, nan]", "material \"white\".color: [0.5, 0.5, NaN] has a non-finite component"),
        (18, "material = \"white\"\nscale = 0", "instance #1.scale: 0 is out of range (must be > 0)"),
        (18, "material = \"white\"\nscale = -2", "instance #1.scale: -2 is out of range"),
        (18, "material = \"white\"\nrotate = [0, nan, 0]", "instance #1.rotate: [0.0, NaN, 0.0] has a non-finite component"),
        (11, "shape = \"sphere\"\nsubdivisions = 8", "mesh \"box\".subdivisions: 8 is out of range (must be in 0..=7)"),
        (4, "fov_y = 40\nfocus_distance = 3\naperture_radius = 0", "camera.aperture_radius: 0 is out of range (must be > 0)"),
    ];
    for &(line, with, expected) in cases {
        let report_line = line + with.lines().count() - 1;
        expect(&edit(line, with), report_line, expected);
    }
    let more: &[(&str, usize, &str)] = &[
        (
            "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 0.8\n",
            22,
            "material \"glass\".ior: 0.8 is out of range (must be in (1, 4])",
        ),
        (
            "[[material]]\nname = \"glass\"\nkind = \"dielectric\"\nior = 4.5\n",
            22,
            "material \"glass\".ior: 4.5 is out of range (must be in (1, 4])",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"plastic\"\ncolor = [1, 1, 1]\nroughness = 1.5\n",
            23,
            "material \"m\".roughness: 1.5 is out of range (must be in [0, 1])",
        ),
        (
            "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nemission = [5, -1, 5]\n",
            22,
            "material \"lamp\".emission: channel 1 of [5.0, -1.0, 5.0] is -1, out of range (must be ≥ 0)",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 2, 0] }\n",
            22,
            "material \"m\".texture.color_b: channel 1 of [0.0, 2.0, 0.0] is 2",
        ),
        (
            "[[material]]\nname = \"m\"\nkind = \"lambertian\"\ntexture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], scale = -1 }\n",
            22,
            "material \"m\".texture.scale: -1 is out of range (must be > 0)",
        ),
        (
            "[[light]]\nkind = \"sphere\"\ncenter = [0, 2, 0]\nradius = 0\nradiance = [1, 1, 1]\n",
            22,
            "light #1.radius: 0 is out of range (must be > 0)",
        ),
        (
            "[[light]]\nkind = \"sphere\"\ncenter = [0, 2, 0]\nradius = 1\nradiance = [1, inf, 1]\n",
            23,
            "light #1.radiance: [1.0, inf, 1.0] has a non-finite component",
        ),
        (
            "[[light]]\nkind = \"quad\"\ncorner = [0, 2, 0]\nedge_u = [1, 0, 0]\nedge_v = [2, 0, 0]\nradiance = [1, 1, 1]\n",
            23,
            "light #1.edge_v: the quad has zero area (edge_u [1, 0, 0] and edge_v [2, 0, 0] are parallel or zero)",
        ),
        (
            "[[light]]\nkind = \"quad\"\ncorner = [0, 2, 0]\nedge_u = [0, 0, 0]\nedge_v = [0, 0, 1]\nradiance = [1, 1, 1]\n",
            23,
            "light #1.edge_v: the quad has zero area",
        ),
        (
            "[environment]\nradiance = [-1, 0, 0]\n",
            20,
            "environment.radiance: channel 0 of [-1.0, 0.0, 0.0] is -1",
        ),
    ];
    for &(text, line, expected) in more {
        expect(&append(text), line, expected);
    }
}

#[test]
fn degenerate_cameras_are_rejected() {
    expect(
        &edit(3, "look_at = [0, 1, 5]"),
        3,
        "camera.look_at: [0, 1, 5] equals camera.position: the view direction is undefined",
    );
    expect(
        &edit(3, "look_at = [0, -3, 5]"),
        1,
        "camera.up: the default up [0, 1, 0] is parallel to the view direction",
    );
    expect(
        &edit(3, "look_at = [0, 1, 0]\nup = [0, 0, -2]"),
        4,
        "camera.up: camera.up is parallel to the view direction",
    );
    expect(
        &edit(3, "look_at = [0, 1, 0]\nup = [0, 0, 0]"),
        4,
        "camera.up: camera.up is parallel",
    );
}

#[test]
fn names_must_be_unique_and_known() {
    expect(
        &edit(17, "mesh = \"boxx\""),
        17,
        "instance #1.mesh: unknown mesh \"boxx\" (defined: \"box\")",
    );
    expect(
        &edit(18, "material = \"red\""),
        18,
        "instance #1.material: unknown material \"red\" (defined: \"white\")",
    );
    expect(
        &append("[[mesh]]\nname = \"box\"\nshape = \"quad\"\n"),
        20,
        "mesh #2.name: duplicate name: mesh \"box\" is already defined on line 10",
    );
    expect(
        &append("[[material]]\nname = \"white\"\nkind = \"lambertian\"\ncolor = [1, 1, 1]\n"),
        20,
        "material #2.name: duplicate name: material \"white\" is already defined on line 13",
    );
    expect(
        &edit(10, "name = \"\""),
        10,
        "mesh #1.name: must not be empty",
    );
}

#[test]
fn a_scene_without_instances_is_rejected() {
    let text: String = BASE.lines().take(15).map(|l| format!("{l}\n")).collect();
    expect(
        &text,
        15,
        "instance: the scene has no [[instance]]: there would be nothing to render",
    );
}

/// A folder with a scene referring to files in it (`files`: name → content).
fn scene_dir(files: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, content) in files {
        std::fs::write(dir.path().join(name), content).unwrap();
    }
    let scene = dir.path().join("scene.toml");
    (dir, scene)
}

#[test]
fn referenced_files_must_exist() {
    let (dir, scene) = scene_dir(&[]);
    let text = edit(11, "path = \"meshes/missing.off\"");
    let e = Scene::parse(&text, &scene).unwrap_err();
    let expected = format!(
        "{}:11: mesh \"box\".path: {} does not exist",
        scene.display(),
        dir.path().join("meshes/missing.off").display()
    );
    assert!(
        matches!(e, SceneError::MissingFile { line: 11, .. }),
        "{e:?}"
    );
    assert_eq!(e.to_string(), expected);

    let text = append("[environment]\npath = \"sky.exr\"\n");
    let e = Scene::parse(&text, &scene).unwrap_err();
    let expected = format!(
        "{}:20: environment.path: {} does not exist",
        scene.display(),
        dir.path().join("sky.exr").display()
    );
    assert_eq!(e.to_string(), expected);

    let text = append("[environment]\npath = \".\"\n");
    let e = Scene::parse(&text, &scene).unwrap_err().to_string();
    assert!(
        e.contains(":20: environment.path: ") && e.ends_with("is not a file"),
        "{e}"
    );

    let e = Scene::load(&dir.path().join("absent.toml")).unwrap_err();
    assert!(matches!(e, SceneError::Io { .. }), "{e:?}");
    assert!(
        e.to_string().contains("absent.toml: cannot read the scene"),
        "{e}"
    );
}

#[test]
fn environment_maps_are_checked_not_decoded() {
    // Not an EXR at all: decoding belongs to the environment loader.
    let (dir, scene) = scene_dir(&[("sky.exr", "not decoded here")]);
    let text = append("[environment]\npath = \"sky.exr\"\nrotation = 90\n");
    let s = Scene::parse(&text, &scene).unwrap();
    assert_eq!(
        s.environment,
        Environment::LatLong {
            path: dir.path().join("sky.exr"),
            intensity: 1.0,
            rotation_deg: 90.0
        }
    );
    let text = append("[environment]\npath = \"sky.exr\"\nintensity = 0\n");
    let e = Scene::parse(&text, &scene).unwrap_err().to_string();
    assert!(
        e.contains(":21: environment.intensity: 0 is out of range (must be > 0)"),
        "{e}"
    );
}

#[test]
fn mesh_errors_keep_their_message_and_add_the_scene_line() {
    let (dir, scene) = scene_dir(&[
        ("bad.off", "OFF\n3 1 0\n0 0 0\n1 zz 0\n0 1 0\n3 0 1 2\n"),
        ("mesh.ply", "ply\n"),
        ("tri.off", "OFF\n3 1 0\n0 0 0\n2 0 0\n0 4 0\n3 0 1 2\n"),
    ]);
    let text = edit(11, "path = \"bad.off\"");
    let e = Scene::parse(&text, &scene).unwrap_err();
    assert!(matches!(e, SceneError::Mesh { line: 11, .. }), "{e:?}");
    let expected = format!(
        "{}:11: mesh \"box\".path: {}:4: vertex 1 coordinate y: \"zz\" is not a number",
        scene.display(),
        dir.path().join("bad.off").display()
    );
    assert_eq!(e.to_string(), expected);

    let text = edit(11, "path = \"mesh.ply\"");
    let e = Scene::parse(&text, &scene).unwrap_err().to_string();
    assert!(e.contains(":11: mesh \"box\".path: "), "{e}");
    assert!(e.contains("unknown mesh format"), "{e}");

    // Normalization is on by default for files and can be turned off.
    let s = Scene::parse(&edit(11, "path = \"tri.off\""), &scene).unwrap();
    assert_eq!(s.meshes[0].mesh.bounds().max, Vec3::new(0.75, 1.0, 0.5));
    let s = Scene::parse(&edit(11, "path = \"tri.off\"\nnormalize = false"), &scene).unwrap();
    assert_eq!(s.meshes[0].mesh.bounds().max, Vec3::new(2.0, 4.0, 0.0));
}

/// Signed volume (positive when the triangles face outwards) and whether every edge is shared
/// by exactly one other triangle running it the other way (closed and consistently oriented).
fn volume_and_closed(m: &Mesh) -> (f64, bool) {
    let mut volume6 = 0.0f64;
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for &[a, b, c] in &m.triangles {
        let [pa, pb, pc] = [a, b, c].map(|i| m.positions[i as usize].as_dvec3());
        volume6 += pa.dot(pb.cross(pc));
        for (u, v) in [(a, b), (b, c), (c, a)] {
            *edges.entry((u, v)).or_default() += 1;
        }
    }
    let closed = edges
        .iter()
        .all(|(&(u, v), &n)| n == 1 && edges.get(&(v, u)) == Some(&1));
    (volume6 / 6.0, closed)
}

#[test]
fn cube_is_closed_outward_and_unit() {
    let cube = Mesh::unit_cube();
    cube.validate().unwrap();
    assert_eq!((cube.positions.len(), cube.triangles.len()), (8, 12));
    let (volume, closed) = volume_and_closed(&cube);
    assert_eq!(volume, 1.0);
    assert!(closed);
    let b = cube.bounds();
    assert_eq!((b.min, b.max), (Vec3::ZERO, Vec3::ONE));
}

#[test]
fn icosphere_is_closed_outward_and_round() {
    let centre = Vec3A::splat(0.5);
    for s in 0..=4 {
        let sphere = Mesh::icosphere(s);
        sphere.validate().unwrap();
        let n = 4usize.pow(s);
        assert_eq!(
            (sphere.positions.len(), sphere.triangles.len()),
            (10 * n + 2, 20 * n)
        );
        let (volume, closed) = volume_and_closed(&sphere);
        assert!(closed, "subdivisions {s}");
        // Inscribed in the sphere of radius 0.5: below its volume, approaching it.
        let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!(volume > 0.6 * ball && volume < ball, "{s}: {volume}");
        for p in &sphere.positions {
            let r = (Vec3A::from(*p) - centre).length();
            assert!((r - 0.5).abs() < 1e-6, "{s}: {p} at {r}");
        }
        for &[a, b, c] in &sphere.triangles {
            let [pa, pb, pc] = [a, b, c].map(|i| Vec3A::from(sphere.positions[i as usize]));
            let normal = (pb - pa).cross(pc - pa);
            assert!(normal.dot((pa + pb + pc) / 3.0 - centre) > 0.0, "{s}");
        }
    }
    let (v4, _) = volume_and_closed(&Mesh::icosphere(4));
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    assert!((v4 - ball).abs() / ball < 0.01, "{v4} vs {ball}");
    assert_eq!(MAX_ICOSPHERE_SUBDIVISIONS, 7);
}

#[test]
fn quad_faces_up_with_unit_area() {
    let quad = Mesh::unit_quad();
    quad.validate().unwrap();
    assert_eq!((quad.positions.len(), quad.triangles.len()), (4, 2));
    let mut area = Vec3::ZERO;
    for &[a, b, c] in &quad.triangles {
        let [pa, pb, pc] = [a, b, c].map(|i| quad.positions[i as usize]);
        area += (pb - pa).cross(pc - pa) * 0.5;
    }
    assert_eq!(area, Vec3::Y);
    let b = quad.bounds();
    assert_eq!((b.min, b.max), (Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)));
}

/// The complete example of `docs/scenes.md` stays valid (its mesh read from the assets, its sky
/// map a placeholder next to it).
#[test]
fn documented_example_loads() {
    let doc = std::fs::read_to_string(repo().join("docs/scenes.md")).unwrap();
    let example = doc
        .find("## A complete example")
        .expect("the example section");
    let start =
        example + doc[example..].find("```toml\n").expect("a toml block") + "```toml\n".len();
    let end = start + doc[start..].find("```").unwrap();
    let bunny = repo().join("assets/meshes/bunny00.off");
    let text = doc[start..end].replace(
        "\"../assets/meshes/bunny00.off\"",
        &format!("{:?}", bunny.display().to_string()),
    );
    let (dir, scene) = scene_dir(&[("sky.exr", "placeholder")]);
    let s = Scene::parse(&text, &scene).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(counts(&s), [3, 4, 4, 2]);
    assert_eq!(s.render.seed, 7);
    assert!(matches!(s.camera.lens, Lens::ThinLens { .. }));
    assert_eq!(
        s.environment,
        Environment::LatLong {
            path: dir.path().join("sky.exr"),
            intensity: 0.8,
            rotation_deg: 90.0
        }
    );
}

#[test]
fn textures_baked_into_stores() {
    use lazysolid_renderer::scene::{StoreFilter, StoreKind, StoreSpec};
    let tex = |extra: &str| {
        edit(
            15,
            &format!(
                "texture = {{ kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0]{extra} }}"
            ),
        )
    };
    let s = parse(&tex(
        ", store = \"octree\", resolution = 256, filter = \"trilinear\"",
    ))
    .unwrap();
    assert_eq!(
        s.materials[0].texture.clone().unwrap().store,
        Some(StoreSpec {
            kind: StoreKind::Octree,
            resolution: 256,
            filter: StoreFilter::Trilinear
        })
    );
    let s = parse(&tex(", store = \"coherent_hash\", resolution = 64")).unwrap();
    assert_eq!(
        s.materials[0]
            .texture
            .clone()
            .unwrap()
            .store
            .unwrap()
            .filter,
        StoreFilter::Nearest
    );
    assert!(parse(&tex("")).unwrap().materials[0]
        .texture
        .clone()
        .unwrap()
        .store
        .is_none());
    expect(
        &tex(", store = \"octree\""),
        15,
        "material \"white\".texture.resolution: is required with `store`",
    );
    expect(
        &tex(", resolution = 64"),
        15,
        "material \"white\".texture.store: is required with `resolution`",
    );
    expect(
        &tex(", store = \"octree\", resolution = 4096"),
        15,
        "material \"white\".texture.resolution: 4096 is out of range (must be in 2..=2048)",
    );
    expect(
        &tex(", filter = \"trilinear\""),
        15,
        "material \"white\".texture.filter: applies only to a texture baked into a store",
    );
    expect(
        &tex(", store = \"octree\", resolution = 2039"),
        15,
        "material \"white\".texture.resolution: 2039 cannot be an octree resolution",
    );
    assert!(parse(&tex(", store = \"coherent_hash\", resolution = 2039")).is_ok());
    let e = error(&tex(", store = \"kd_tree\", resolution = 64"));
    assert!(
        e.contains("scenes/t.toml:15") && e.contains("kd_tree"),
        "{e}"
    );
    // Every structure has a name; the error for an unknown one lists them.
    for name in ["coherent_hash", "octree", "perfect_hash", "tiletree"] {
        assert!(e.contains(&format!("`{name}`")), "{e}");
        for (filter, want) in [
            ("nearest", StoreFilter::Nearest),
            ("trilinear", StoreFilter::Trilinear),
        ] {
            let s = parse(&tex(&format!(
                ", store = \"{name}\", resolution = 128, filter = \"{filter}\""
            )))
            .unwrap();
            let spec = s.materials[0].texture.clone().unwrap().store.unwrap();
            assert_eq!((spec.kind.name(), spec.filter), (name, want));
        }
    }
    assert_eq!(
        parse(&tex(", store = \"tiletree\", resolution = 64"))
            .unwrap()
            .materials[0]
            .texture
            .clone()
            .unwrap()
            .store
            .unwrap()
            .kind,
        StoreKind::TileTree
    );
    expect(
        &tex(", store = \"tiletree\", resolution = 100"),
        15,
        "material \"white\".texture.resolution: 100 cannot be a tiletree resolution",
    );
    assert!(parse(&tex(", store = \"perfect_hash\", resolution = 100")).is_ok());
    expect(
        &tex(", store = \"perfect_hash\", resolution = 64, filter = \"cubic\""),
        15,
        "material \"white\".texture.filter: unknown variant `cubic`",
    );
}

#[test]
fn volume_textures_read_their_file_through_a_store() {
    // Red then blue along x.
    let nrrd = b"NRRD0004\ntype: uint8\ndimension: 4\nsizes: 3 2 1 1\nencoding: raw\n\n\xff\x00\x00\x00\x00\xff";
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("v.nrrd"), nrrd).unwrap();
    std::fs::write(dir.path().join("bad.nrrd"), b"P6\n").unwrap();
    let scene = dir.path().join("scene.toml");
    let tex = |body: &str| edit(15, &format!("texture = {{ kind = \"volume\"{body} }}"));
    let store = ", store = \"octree\", resolution = 64";
    let s = Scene::parse(&tex(&format!(", path = \"v.nrrd\"{store}")), &scene).unwrap();
    let t = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(t.kind, SolidTextureKind::Volume);
    let v = t.volume.as_ref().unwrap();
    assert_eq!(v.size, [2, 1, 1]);
    assert_eq!(v.at_voxel([31, 0, 0], 64), [255, 0, 0]);
    assert_eq!(v.at_voxel([32, 63, 63], 64), [0, 0, 255]);
    // The flat preview colour is the mean in linear RGB.
    assert!((s.materials[0].color - glam::Vec3::new(0.5, 0.0, 0.5)).length() < 1e-6);

    let err = |text: String| Scene::parse(&text, &scene).unwrap_err().to_string();
    for (body, needle) in [
        (
            ", path = \"v.nrrd\"".to_string(),
            "material \"white\".texture.store: missing: a volume texture is read through a store",
        ),
        (
            store.to_string(),
            "material \"white\".texture.path: missing (a volume texture names its NRRD file)",
        ),
        (
            format!(", path = \"v.nrrd\", color_a = [1, 1, 1]{store}"),
            "material \"white\".texture.color_a: a volume texture has its colours in its file",
        ),
        (
            format!(", path = \"v.nrrd\", scale = 2{store}"),
            "material \"white\".texture.scale: a volume texture",
        ),
        (
            format!(", path = \"absent.nrrd\"{store}"),
            "absent.nrrd does not exist",
        ),
        (
            format!(", path = \"bad.nrrd\"{store}"),
            "bad.nrrd: not an NRRD file",
        ),
    ] {
        let e = err(tex(&body));
        assert!(
            e.contains(":15: ") && e.contains(needle),
            "{needle:?} in {e}"
        );
    }
    let e = err(edit(
        15,
        "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], path = \"v.nrrd\" }",
    ));
    assert!(
        e.contains("material \"white\".texture.path: only kind = \"volume\" reads a file"),
        "{e}"
    );
    let e = err(edit(
        15,
        "texture = { kind = \"marble\", color_a = [1, 1, 1] }",
    ));
    assert!(
        e.contains("material \"white\".texture.color_b: missing"),
        "{e}"
    );
}

/// `kind = "synthesized"`: an exemplar by path (relative to the scene) or asset name, read
/// through a store; a missing file, an unknown name, an unreadable image and a missing store
/// each name the file, the line and the field.
#[test]
fn synthesized_textures_name_their_exemplar_and_store() {
    let (dir, scene) = scene_dir(&[("bad.png", "not a png")]);
    image::RgbImage::new(8, 8)
        .save(dir.path().join("tiny.png"))
        .unwrap();
    let texture = |fields: &str| {
        edit(
            15,
            &format!("texture = {{ kind = \"synthesized\", {fields} }}"),
        )
    };
    let e = Scene::parse(
        &texture("exemplar = \"ex/missing.png\", resolution = 64, store = \"coherent_hash\""),
        &scene,
    )
    .unwrap_err();
    assert!(
        matches!(e, SceneError::MissingFile { line: 15, .. }),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!(
            "{}:15: material \"white\".texture.exemplar: {} does not exist",
            scene.display(),
            dir.path().join("ex/missing.png").display()
        )
    );
    let e = Scene::parse(
        &texture("exemplar = \"bad.png\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ") && e.contains("bad.png"),
        "{e}"
    );
    let e = Scene::parse(
        &texture("exemplar = \"no_such_exemplar\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ")
            && (e.contains("no exemplar named \"no_such_exemplar\"") || e.contains("assets/")),
        "{e}"
    );
    expect(
        &texture("exemplar = \"leather\""),
        15,
        "material \"white\".texture.store: missing: a synthesized texture is read through a store",
    );
    // An image of any size is fitted by `lazysolid solid`'s rule, which the render reports.
    let s = Scene::parse(
        &texture("exemplar = \"ground1\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().fit.to_string(),
        "ground1.pat 100x100 RGB → Lanczos3 resample 128x128"
    );
    let e = Scene::parse(
        &texture("exemplar = \"tiny.png\", resolution = 64, store = \"octree\""),
        &scene,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.exemplar: ")
            && e.contains("tiny.png: the image is 8x8; solid synthesis needs at least 16"),
        "{e}"
    );
    expect(
        &texture("exemplar = \"leather\", resolution = 64, store = \"kd_tree\""),
        15,
        "material \"white\".texture.store",
    );
    expect(
        &edit(
            15,
            "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], seed = 3 }",
        ),
        15,
        "material \"white\".texture.seed",
    );
    // The synthesis state's memory policy: "keep" or a budget in MB; anything else, or the
    // field on another kind, is refused with the field.
    let s = Scene::parse(
        &texture("exemplar = \"leather\", resolution = 64, store = \"octree\", memory = \"keep\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().policy,
        lazysolid_synth::solid::lazy::MemoryPolicy::Keep
    );
    for bad in ["lots", "0MB", "12"] {
        let e = Scene::parse(
            &texture(&format!(
                "exemplar = \"leather\", resolution = 64, store = \"octree\", memory = \"{bad}\""
            )),
            &scene,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains(":15: material \"white\".texture.memory: ")
                && e.contains("\"keep\" or a budget in whole MB"),
            "{bad}: {e}"
        );
    }
    expect(
        &edit(
            15,
            "texture = { kind = \"marble\", color_a = [1, 1, 1], color_b = [0, 0, 0], memory = \"keep\" }",
        ),
        15,
        "material \"white\".texture.memory",
    );
}

/// `relief` on a synthesized texture read through a filtered store: its slope is kept; out of
/// range, not finite, on a nearest store, or on a texture without a feature channel it is
/// refused with the field, the line and the limit.
#[test]
fn relief_is_a_synthesized_texture_field_with_a_stated_range() {
    let (_dir, scene) = scene_dir(&[]);
    let texture = |fields: &str| {
        edit(
            15,
            &format!("texture = {{ kind = \"synthesized\", exemplar = \"cracked\", resolution = 64, {fields} }}"),
        )
    };
    let s = Scene::parse(
        &texture("store = \"coherent_hash\", filter = \"trilinear\", relief = 0.75"),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(spec.synthesized.as_ref().unwrap().relief, 0.75);
    let s = Scene::parse(
        &texture("store = \"tiletree\", filter = \"trilinear\""),
        &scene,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let spec = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(
        spec.synthesized.as_ref().unwrap().relief,
        0.0,
        "no relief by default"
    );
    for (bad, why) in [
        ("-0.5", "is out of range (must be in [0, 4]"),
        ("4.5", "is out of range (must be in [0, 4]"),
        ("nan", "is not finite"),
        ("inf", "is not finite"),
    ] {
        let e = Scene::parse(
            &texture(&format!(
                "store = \"octree\", filter = \"trilinear\", relief = {bad}"
            )),
            &scene,
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains(":15: material \"white\".texture.relief: ") && e.contains(why),
            "{bad}: {e}"
        );
    }
    let e = Scene::parse(&texture("store = \"octree\", relief = 1"), &scene)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(":15: material \"white\".texture.relief: needs a filtered store (filter = \"trilinear\")"),
        "{e}"
    );
    expect(
        &edit(
            15,
            "texture = { kind = \"checker\", color_a = [1, 1, 1], color_b = [0, 0, 0], relief = 1 }",
        ),
        15,
        "material \"white\".texture.relief: relief is read from a synthesized texture's feature channel",
    );
}

/// BASE with its box named `b`, followed by `more` (which starts on line 20).
fn broken(more: &str) -> String {
    append(&format!("name = \"b\"\n{more}"))
}

/// `[[fracture]]` and `[[cut]]` replace the named instance by closed pieces of its mesh (in its
/// coordinates, cap faces marked) whose volumes add up to the mesh's; everything else stays.
#[test]
fn fractures_and_cuts_replace_the_instance_by_closed_pieces() {
    use lazysolid_renderer::fracture::{edge_report, volume};
    for (more, pieces) in [
        ("[[fracture]]\ninstance = \"b\"\npieces = 5\nseed = 4\n", 5),
        (
            "[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.3, 0.5]\nnormal = [0, 1, 0]\n\
             [[cut]]\ninstance = \"b\"\npoint = [0.4, 0.5, 0.5]\nnormal = [1, 0, 0.2]\n",
            4,
        ),
        (
            "[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.5, 0.5]\nnormal = [0, 0, 1]\n\
             [[fracture]]\ninstance = \"b\"\nsites = [[0.2, 0.5, 0.5], [0.8, 0.5, 0.5]]\n",
            4,
        ),
    ] {
        let s = parse(&broken(more)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.instances.len(), pieces, "{more}");
        let mut sum = 0.0;
        for inst in &s.instances {
            let piece = inst.piece.expect("every instance is a piece");
            assert_eq!(piece.broken, 0);
            let m = &s.meshes[inst.mesh];
            let (from, caps) = m.cut_from.as_ref().expect("cut from the box");
            assert_eq!(*from, 0);
            assert_eq!(caps.len(), m.mesh.triangles.len());
            assert!(caps.iter().any(|&c| c) && caps.iter().any(|&c| !c));
            assert!(edge_report(&m.mesh.triangles).is_closed(), "{more}");
            sum += volume(&m.mesh.positions, &m.mesh.triangles);
        }
        assert!((sum - 1.0).abs() < 1e-5, "{more}: volumes sum to {sum}");
    }
}

/// Pieces stay at rest until the explosion starts, then move rigidly: their centre of mass
/// flies away from the centre at the given speed and falls; lookups keep rest-pose object
/// coordinates, so only the transform changes.
#[test]
fn pieces_fly_apart_rigidly_after_the_start() {
    let s = parse(&broken(
        "[[fracture]]\ninstance = \"b\"\npieces = 3\nseed = 1\n\
         [explosion]\ncentre = [0.5, 0.5, 0.5]\nspeed = 2\nspin = 45\ngravity = [0, -1, 0]\nstart = 0.5\n\
         [animation]\nframes = 10\nfps = 4\n",
    ))
    .unwrap();
    let a = s.animation.unwrap();
    assert_eq!((a.frames, a.fps), (10, 4.0));
    assert_eq!(s.frame_time(3), 0.75);
    for (i, inst) in s.instances.iter().enumerate() {
        let p = inst.piece.unwrap();
        assert_eq!(s.instance_transform(i, 0.5), inst.transform);
        let t = 1.5;
        let m = s.instance_transform(i, t);
        let at = inst.transform.transform_point3(p.centroid);
        let away = (at - Vec3::splat(0.5)).normalize();
        let want = at + away * 2.0 * 1.0 + Vec3::new(0.0, -0.5, 0.0);
        assert!((m.transform_point3(p.centroid) - want).length() < 1e-4);
        // Rigid: distances between the piece's vertices are kept.
        let v = &s.meshes[inst.mesh].mesh.positions;
        let d0 = v[0].distance(v[v.len() / 2]);
        let d1 = m
            .transform_point3(v[0])
            .distance(m.transform_point3(v[v.len() / 2]));
        assert!((d0 - d1).abs() < 1e-5);
    }
}

#[test]
fn fracture_errors_name_the_line_and_field() {
    expect(
        &broken("[[fracture]]\ninstance = \"x\"\npieces = 2\n"),
        21,
        "fracture #1.instance: unknown instance \"x\" (named instances: \"b\")",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\npieces = 0\n"),
        22,
        "fracture #1.pieces",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\npieces = 2\nsites = [[0, 0, 0]]\n"),
        23,
        "fracture #1.sites: pieces and sites are exclusive",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\n"),
        21,
        "fracture #1: needs pieces = N (random sites) or sites",
    );
    expect(
        &broken("[[cut]]\ninstance = \"b\"\npoint = [0.5, 3, 0.5]\nnormal = [0, 1, 0]\n"),
        22,
        "cut #1.point: the plane through [0.5, 3, 0.5] with normal [0, 1, 0] misses the mesh",
    );
    expect(
        &broken("[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.5, 0.5]\nnormal = [0, 0, 0]\n"),
        23,
        "cut #1.normal: must not be zero",
    );
    expect(
        &broken("[explosion]\nspeed = 1\n"),
        20,
        "explosion: nothing to blow apart",
    );
    expect(
        &broken("[animation]\nframes = 4\nfps = 0\n"),
        22,
        "animation.fps",
    );
    // An open surface bounds no solid: the quad has 4 boundary edges.
    let open = BASE.replace("shape = \"cube\"", "shape = \"quad\"");
    let e = error(&format!(
        "{open}name = \"b\"\n[[fracture]]\ninstance = \"b\"\npieces = 2\n"
    ));
    assert!(
        e.contains("not closed") && e.contains("4 boundary edge"),
        "{e}"
    );
}

/// The main job's scene: the armadillo broken into 14 closed pieces sharing its synthesized
/// texture, an explosion, and an animation rendered smaller than the still.
#[test]
fn explosion_scene_loads() {
    let s = example("explosion.toml");
    assert_eq!(s.instances.len(), 15);
    assert_eq!(s.instances.iter().filter(|i| i.piece.is_some()).count(), 14);
    let e = s.explosion.expect("an explosion");
    assert_eq!((e.speed, e.start), (1.6, 0.25));
    assert_eq!(s.render.spp, 32);
    let a = s.animation.expect("an animation");
    assert_eq!((a.frames, a.width, a.height, a.spp), (16, 320, 240, 8));
    assert_eq!((s.render.width, s.render.height), (640, 480));
    let synthesized = s.materials[0].texture.as_ref().unwrap();
    assert_eq!(synthesized.kind, SolidTextureKind::Synthesized);
    assert!(
        synthesized.synthesized.as_ref().unwrap().relief > 0.0,
        "the main job shows the matter's relief"
    );
}

/// The lowest point of every piece, along the explosion's "up", in each frame of the scene's
/// animation (sampled four times per frame): per frame, the minimum over pieces, and the
/// minimum over pieces of their own lowest point at rest.
fn lowest_per_frame(s: &Scene) -> (Vec<f32>, f32) {
    let e = s.explosion.unwrap();
    let up = e.up();
    let a = s.animation.unwrap();
    let lowest_at = |i: usize, t: f32| {
        let m = s.instance_transform(i, t);
        s.meshes[s.instances[i].mesh]
            .mesh
            .positions
            .iter()
            .map(|&p| up.dot(m.transform_point3(p)))
            .fold(f32::INFINITY, f32::min)
    };
    let pieces: Vec<usize> = (0..s.instances.len())
        .filter(|&i| s.instances[i].piece.is_some())
        .collect();
    let rest = pieces
        .iter()
        .map(|&i| lowest_at(i, 0.0))
        .fold(f32::INFINITY, f32::min);
    let frames = (0..a.frames * 4)
        .map(|k| {
            let t = k as f32 / (4.0 * a.fps);
            pieces
                .iter()
                .map(|&i| lowest_at(i, t))
                .fold(f32::INFINITY, f32::min)
        })
        .collect();
    (frames, rest)
}

/// With `[explosion] ground`, no piece of the main job's scene or the fracture test scene goes
/// below the ground (or below its own rest height, for pieces standing on it) in any frame;
/// without it the same pieces do, so the check can fail. Pieces that touch it keep their pose.
#[test]
fn pieces_stop_on_the_ground() {
    for name in ["explosion.toml", "test/fracture.toml"] {
        let s = example(name);
        let e = s.explosion.unwrap();
        let ground = e.ground.expect("the scene has a ground");
        let (frames, rest) = lowest_per_frame(&s);
        let floor = ground.min(rest);
        for (k, &h) in frames.iter().enumerate() {
            assert!(
                h >= floor - 1e-4,
                "{name} sample {k}: lowest point {h} below {floor}"
            );
        }
        let stopped = s
            .instances
            .iter()
            .filter(|i| i.piece.is_some_and(|p| p.contact.is_some()))
            .count();
        println!("{name}: ground {ground}, rest {rest}, {stopped} piece(s) stop on it, lowest per frame {frames:?}");
        assert!(stopped > 0, "{name}: no piece reaches the ground");
        // A stopped piece keeps its pose.
        for (i, inst) in s.instances.iter().enumerate() {
            if let Some(c) = inst.piece.and_then(|p| p.contact) {
                let t = e.start + c;
                assert_eq!(
                    s.instance_transform(i, t + 2.0),
                    s.instance_transform(i, t + 0.5)
                );
            }
        }
        // Without the ground, pieces fall through it.
        let mut free = s.clone();
        for inst in &mut free.instances {
            if let Some(p) = &mut inst.piece {
                p.contact = None;
            }
        }
        let (frames, _) = lowest_per_frame(&free);
        let deepest = frames.iter().copied().fold(f32::INFINITY, f32::min);
        assert!(
            deepest < floor - 0.05,
            "{name}: without a ground the lowest point is {deepest}"
        );
    }
    expect(
        &broken(
            "[[fracture]]\ninstance = \"b\"\npieces = 2\n[explosion]\nspeed = 1\nground = 1e9\n",
        ),
        25,
        "explosion.ground",
    );
}

/// Names refer to the named instance wherever it stands among unnamed ones; a name used twice
/// is refused at its second use.
#[test]
fn instance_names_find_the_right_instance() {
    let text = format!(
        "{BASE}[[instance]]\nname = \"b\"\nmesh = \"box\"\nmaterial = \"white\"\ntranslate = [3, 0, 0]\n\
         [[fracture]]\ninstance = \"b\"\npieces = 2\n"
    );
    let s = parse(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.instances.len(), 3);
    assert!(
        s.instances[0].piece.is_none(),
        "the unnamed box stays whole"
    );
    for inst in &s.instances[1..] {
        assert_eq!(inst.piece.unwrap().broken, 1);
        assert_eq!(inst.transform.translation.x, 3.0);
    }
    let twice = format!(
        "{BASE}name = \"b\"\n[[instance]]\nname = \"b\"\nmesh = \"box\"\nmaterial = \"white\"\n"
    );
    expect(
        &twice,
        21,
        "instance #2.name: duplicate name: instance \"b\" is already defined on line 19",
    );
}
