//! Compiles the renderer's kernels (`glsl/render/*.comp`; the test-only kernels of
//! `glsl/render_test/` are the tests crate's) into `kernels.rs` (see the
//! `lazysolid-shader-build` crate), with the compute crate's constants (the store includes use
//! them) and the renderer's own. A GLSL error fails the build with the file and line.

use lazysolid_shader_build::{build_kernels, dependency_constants, export_constants, KernelSet};
use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let set = KernelSet {
        glsl_root: manifest.join("../glsl"),
        folders: vec!["render".into()],
        constants: dependency_constants("lazysolid_compute")
            .into_iter()
            .chain([manifest.join("src/shader_constants.rs")])
            .collect(),
        gpu_module: "lazysolid_compute::gpu".into(),
    };
    build_kernels(&set);
    export_constants(&set);
}
