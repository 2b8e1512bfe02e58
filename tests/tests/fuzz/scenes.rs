//! Scene TOML (`Scene::parse`): every table and field of the scenes the project ships, each
//! seed parsed where it lives (so its meshes, maps and exemplars resolve), and a file that is
//! not UTF-8 read through `Scene::load`.

use crate::oracle::{self, MIB};
use crate::{mutate, regressions, repo, write_case, Seed};
use lazysolid_renderer::scene::Scene;
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// What a scene may hold beyond its meshes and maps: a count in it (frames, pieces, samples)
/// must not reserve memory before the render asks for it.
const BOUND: usize = 256 * MIB;

/// Parses `bytes` as if they were the scene file `path`: in place when they are text, else
/// through a temporary copy, whose read must fail with its path.
fn read(path: &Path, bytes: &[u8]) -> Result<(), String> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Scene::parse(text, path)
            .map(|_| ())
            .map_err(|e| e.to_string()),
        Err(_) => {
            let name = path.file_name().unwrap().to_string_lossy();
            let (_dir, copy) = write_case(&name, bytes);
            Scene::load(&copy).map(|_| ()).map_err(|e| e.to_string())
        }
    }
}

/// The scenes whose meshes load in milliseconds: every material kind (Lambertian, conductor,
/// plastic, glass, glint, image, procedural, volume, synthesized, normal and height maps),
/// lights, motion, cuts and fractures. The armadillo's scenes differ from these in the mesh
/// only, and loading it takes most of a second in a debug build.
const SCENES: &[&str] = &[
    "scenes/default.toml",
    "scenes/glints.toml",
    "scenes/test/fracture.toml",
    "scenes/test/glass_metal.toml",
    "scenes/test/interior.toml",
    "scenes/test/relief.toml",
    "scenes/test/textured.toml",
    "scenes/normal-maps/v-groove.toml",
];

/// Every key of every scene table (`renderer/src/scene/raw.rs`) and every table header.
const KEYS: &[&str] = &[
    "albedo_ctree_step",
    "albedo_map",
    "animation",
    "aperture_radius",
    "blend",
    "camera",
    "center",
    "centre",
    "color",
    "color_a",
    "color_b",
    "corner",
    "cut",
    "edge_u",
    "edge_v",
    "emission",
    "environment",
    "evaluation",
    "exemplar",
    "explosion",
    "filter",
    "focus_distance",
    "fov_y",
    "fps",
    "fracture",
    "frames",
    "gravity",
    "ground",
    "height",
    "height_map",
    "height_scale",
    "instance",
    "intensity",
    "intrinsic_roughness",
    "ior",
    "k",
    "kind",
    "light",
    "look_at",
    "material",
    "max_depth",
    "memory",
    "mesh",
    "name",
    "normal",
    "normal_filter",
    "normal_map",
    "normalize",
    "patch",
    "path",
    "pieces",
    "point",
    "position",
    "preset",
    "radiance",
    "radius",
    "relief",
    "render",
    "resolution",
    "rotate",
    "rotation",
    "roughness",
    "rr_depth",
    "scale",
    "seed",
    "shape",
    "sites",
    "speed",
    "spin",
    "spp",
    "start",
    "store",
    "subdivisions",
    "texture",
    "translate",
    "two_sided",
    "up",
    "uv",
    "vmf_lobes",
    "width",
];
const TABLES: &[&str] = &[
    "[camera]",
    "[render]",
    "[environment]",
    "[explosion]",
    "[animation]",
    "[[mesh]]",
    "[[material]]",
    "[[instance]]",
    "[[light]]",
    "[[cut]]",
    "[[fracture]]",
];

fn seeds() -> &'static [(PathBuf, Seed)] {
    static SEEDS: OnceLock<Vec<(PathBuf, Seed)>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        SCENES
            .iter()
            .map(|f| {
                let path = repo().join(f);
                (path.clone(), Seed::file(&path))
            })
            .collect()
    })
}

#[test]
fn the_seeds_are_read() {
    for (path, s) in seeds() {
        read(path, &s.bytes).unwrap_or_else(|e| panic!("seed {}: {e}", s.name));
    }
}

#[test]
fn regression_cases() {
    for file in regressions("scenes") {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let bytes = std::fs::read(&file).unwrap();
        let case = oracle::Case {
            format: "scenes",
            name: &name,
            bytes: &bytes,
        };
        oracle::check(&case, BOUND, || read(&file, &bytes)).unwrap();
    }
}

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_scenes(
        seed in 0..seeds().len(),
        edits in mutate::mutations_with(mutate::toml_dictionary(KEYS, TABLES)),
    ) {
        let (path, s) = &seeds()[seed];
        let bytes = mutate::apply(&s.bytes, &edits);
        let case = oracle::Case {
            format: "scenes",
            name: &s.name,
            bytes: &bytes,
        };
        oracle::check(&case, BOUND, || read(path, &bytes))?;
    }
}
