//! Compiles the kernels this crate owns (`glsl/{prims,hash,store,voxel,ctree}/*.comp`) into
//! `kernels.rs` (see the `lazysolid-shader-build` crate). A GLSL error fails the build with the
//! file and line. The synthesizer's kernels (`glsl/synth/`) are compiled by `lazysolid-synth`,
//! the renderer's (`glsl/render/`) by the renderer.

use lazysolid_shader_build::{build_kernels, export_constants, KernelSet};
use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let set = KernelSet {
        glsl_root: manifest.join("../glsl"),
        folders: ["prims", "hash", "store", "voxel", "ctree"]
            .map(String::from)
            .to_vec(),
        constants: vec![manifest.join("src/shader_constants.rs")],
        gpu_module: "crate::gpu".into(),
    };
    build_kernels(&set);
    export_constants(&set);
}
