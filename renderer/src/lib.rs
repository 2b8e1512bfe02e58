//! lazysolid's renderer crate: meshes, scenes and the path tracer.
//!
//! - [`mesh`]: OBJ (tobj) and OFF loading, built-in shapes, the unit-cube normalization.
//! - [`scene`]: the TOML scene loader (`docs/scenes.md`) and the resolved scene types.
//! - [`accel`]: obvhs CWBVHs per mesh and over instances, uploaded for the GLSL traversal.
//! - [`shading`]: the GPU records of materials, lights and environment, with a CPU reference
//!   of the GLSL shading library.
//! - [`fracture`]: plane cuts and Voronoi fracture of closed meshes into closed, capped pieces.
//! - [`glint`]: the infinite glint microstructure by example (point and range queries).
//! - [`normal_map`]: von Mises–Fisher lobes and their spherical EM fit (normal-map filtering).
//! - [`render`]: the path-tracing kernel's driver (progressive passes into a float film).
//! - [`output`] and [`diff`]: EXR/PNG writing and FLIP image comparison.
//! - [`kernels`] and [`shader_constants`]: the renderer's GLSL kernels (`glsl/render/`), compiled
//!   by `build.rs`, and the constants they share with the Rust code.

pub mod accel;
pub mod assets;
mod bake;
pub mod diff;
pub mod export;
pub mod fracture;
pub mod glint;
pub mod image_texture;
pub mod mesh;
pub mod normal_map;
pub mod output;
mod push_registry;
pub mod render;
pub mod scene;
pub mod shader_constants;
pub mod shading;

/// Kernels compiled from `glsl/render/` at build time.
pub mod kernels {
    include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
}

pub use push_registry::push_registry;
