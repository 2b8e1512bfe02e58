//! The scenes the repository ships and the complete example of `docs/scenes.md`: each loads, and
//! the main ones (default, textured, glass and metal, interior, normal maps) carry the meshes,
//! materials, lights and settings they are written with, so an edit to a scene file or to the
//! loader that changes what a user renders is caught here.

use crate::support::{counts, example, repo, scene_dir};
use glam::Vec3;
use lazysolid_renderer::mesh::Mesh;
use lazysolid_renderer::scene::{Environment, Lens, Light, MaterialKind, Scene, SolidTextureKind};
use std::path::PathBuf;

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
