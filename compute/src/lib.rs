//! lazysolid's compute crate: an explicit Vulkan compute core (ash + gpu-allocator), the GPU
//! primitives every structure builder uses (scan, compaction, reduce, radix sort), the spatial
//! hashes, the voxelizer and the sparse texture stores. The synthesizer that fills the stores is
//! the `lazysolid-synth` crate, built on this one.
//!
//! Every GPU kernel has a plain-Rust reference next to it; tests compare the two.

pub mod atomic_file;
pub mod ctree;
pub mod gpu;
pub mod hash;
pub mod host_memory;
pub mod prims;
mod push_registry;
pub mod shader_constants;
pub mod store;
pub mod texel;
pub mod voxel;

/// Kernels compiled from `glsl/` at build time, one module per folder.
pub mod kernels {
    include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
}

pub use ash;
pub use gpu_allocator;
pub use push_registry::push_registry;
