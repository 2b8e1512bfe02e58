//! Compiles the test-only kernels (`glsl/render_test/*.comp`: the shading and glint entry
//! points dispatched case by case against their CPU references) into `kernels.rs`, with the
//! renderer's constants (their includes are the renderer's) and the tests' own. They live here
//! so that no production build compiles or embeds them.

use lazysolid_shader_build::{build_kernels, dependency_constants, KernelSet};
use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    build_kernels(&KernelSet {
        glsl_root: manifest.join("../glsl"),
        folders: vec!["render_test".into()],
        constants: dependency_constants("lazysolid_renderer")
            .into_iter()
            .chain([manifest.join("src/shader_constants.rs")])
            .collect(),
        gpu_module: "lazysolid_compute::gpu".into(),
    });
}
