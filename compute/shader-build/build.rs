//! Debian's `libshaderc.so.1` lacks its glslang dependencies and cannot be linked, so shaderc is
//! linked statically (`prefer-static-linking`) together with Debian's static glslang and
//! SPIRV-Tools archives. Emitting the libraries here makes every artifact that links this crate
//! (notably `compute/build.rs`) link them too.
fn main() {
    println!("cargo:rustc-link-search=native=/usr/lib/x86_64-linux-gnu");
    for l in [
        "glslang",
        "MachineIndependent",
        "GenericCodeGen",
        "OSDependent",
        "OGLCompiler",
        "SPIRV",
        "HLSL",
        "glslang-default-resource-limits",
        "SPIRV-Tools-opt",
        "SPIRV-Tools",
    ] {
        println!("cargo:rustc-link-lib=static={l}");
    }
}
