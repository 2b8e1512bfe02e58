//! Compiles the synthesizer's kernels (`glsl/synth/**/*.comp`) into `kernels.rs` (see the
//! `lazysolid-shader-build` crate), with the compute crate's constants (the lazy kernels use its
//! hash constants) and the synthesizer's own. A GLSL error fails the build with the file and
//! line.

use lazysolid_shader_build::{build_kernels, dependency_constants, KernelSet};
use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    build_kernels(&KernelSet {
        glsl_root: manifest.join("../glsl"),
        folders: vec!["synth".into()],
        constants: dependency_constants("lazysolid_compute")
            .into_iter()
            .chain([manifest.join("src/shader_constants.rs")])
            .collect(),
        gpu_module: "lazysolid_compute::gpu".into(),
    });
}
