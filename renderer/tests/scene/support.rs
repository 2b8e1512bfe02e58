//! What every module of the test binary shares: the shipped scenes by name, `BASE` (a minimal
//! valid scene whose line numbers the error tests count on) with the helpers that edit it and
//! check the `file:line: field: message` of a refused scene, a folder for scenes that refer to
//! files, and `broken` (BASE with its instance named, for `[[fracture]]` and `[[cut]]`).

use lazysolid_renderer::scene::{Scene, SceneError};
use std::path::{Path, PathBuf};

pub(crate) fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

pub(crate) fn example(name: &str) -> Scene {
    let path = repo().join("scenes").join(name);
    Scene::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Mesh, material, instance and light counts.
pub(crate) fn counts(s: &Scene) -> [usize; 4] {
    [
        s.meshes.len(),
        s.materials.len(),
        s.instances.len(),
        s.lights.len(),
    ]
}

/// A minimal valid scene; the line numbers of its keys are what the error tests expect.
pub(crate) const BASE: &str = r#"[camera]
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

pub(crate) fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::parse(text, Path::new(FILE))
}

/// The error message of a scene that must fail.
pub(crate) fn error(text: &str) -> String {
    match parse(text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// Checks that `text` fails with a message containing `FILE:line: expected`.
pub(crate) fn expect(text: &str, line: usize, expected: &str) {
    let e = error(text);
    let want = format!("{FILE}:{line}: {expected}");
    assert!(
        e.contains(&want),
        "expected {want:?}\n got {e:?}\nfor\n{text}"
    );
}

/// BASE with one line replaced (1-based) by `with` (which may span several lines).
pub(crate) fn edit(line: usize, with: &str) -> String {
    let mut lines: Vec<&str> = BASE.lines().collect();
    lines[line - 1] = with;
    lines.join("\n") + "\n"
}

/// BASE followed by `more` (its first line is line 19).
pub(crate) fn append(more: &str) -> String {
    format!("{BASE}{more}")
}

/// A folder with a scene referring to files in it (`files`: name → content).
pub(crate) fn scene_dir(files: &[(&str, &str)]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    for (name, content) in files {
        std::fs::write(dir.path().join(name), content).unwrap();
    }
    let scene = dir.path().join("scene.toml");
    (dir, scene)
}

/// BASE with its box named `b`, followed by `more` (which starts on line 20).
pub(crate) fn broken(more: &str) -> String {
    append(&format!("name = \"b\"\n{more}"))
}
