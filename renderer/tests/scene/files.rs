//! The files a scene refers to, resolved next to the scene: missing files and folders are
//! refused with the path, environment maps are only checked (decoding is the environment
//! loader's), and mesh errors keep the mesh file's own line under the scene's.

use crate::support::{append, edit, scene_dir};
use glam::Vec3;
use lazysolid_renderer::scene::{Environment, Scene, SceneError};

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
