//! Compiles `glsl/**/*.comp` into `kernels.rs` (see the `lazysolid-shader-build` crate). A GLSL
//! error fails the build with the file and line.

use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap());
    let glsl = manifest.join("../glsl");
    let constants = manifest.join("src/shader_constants.rs");
    println!("cargo:rerun-if-changed={}", glsl.display());
    println!("cargo:rerun-if-changed={}", constants.display());
    match lazysolid_shader_build::generate(&glsl, &constants) {
        Ok(source) => std::fs::write(
            PathBuf::from(std::env::var("OUT_DIR").unwrap()).join("kernels.rs"),
            source,
        )
        .unwrap(),
        Err(e) => {
            eprintln!("{e}");
            panic!("{e}");
        }
    }
}
