//! Shading: the GPU records of materials, lights and the environment that the path tracer
//! reads, and a CPU reference of every shading function the GLSL library
//! (`glsl/include/render/*.glsl`) provides, so that tests can hold the kernels to it.
//!
//! Directions given to BSDFs are in the local shading frame: z is the surface's outward normal
//! and `wo` points back along the path (see `glsl/include/render/bsdf.glsl`).

mod coat;
mod environment_map;
mod error;
mod gpu_environment;
mod light;
mod material;
pub mod reference;

pub use coat::{coat_albedo_at, coat_terms, CoatTerms, COAT_KNOTS};
pub use environment_map::{EnvironmentMap, MAX_ENVIRONMENT_TEXELS};
pub use error::ShadingError;
pub use gpu_environment::{EnvironmentParams, GpuEnvironment};
pub use light::GpuLight;
pub use material::GpuMaterial;
