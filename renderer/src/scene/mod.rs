//! Scenes: the resolved scene types and the TOML scene loader ([`Scene::load`],
//! [`Scene::parse`]).
//!
//! The format (every table, key, default and limit, with a complete example) is described in
//! one place only: `docs/scenes.md`. Every error names the scene file, the line and the field
//! path, e.g. `scenes/a.toml:14: material "glass".ior: 0.8 is out of range (must be in (1, 4])`.

mod broken;
mod camera;
mod check;
mod error;
mod lights;
mod location;
mod material;
mod meshes;
mod motion;
mod raw;
mod resolve;
mod types;
mod volume;

pub use camera::{DEFAULT_MAX_DEPTH, DEFAULT_RR_DEPTH, MAX_DEPTH, MAX_IMAGE_SIDE, MAX_SPP};
pub use error::SceneError;
pub use meshes::DEFAULT_SPHERE_SUBDIVISIONS;
pub use types::*;
pub use volume::{VolumeTexture, MAX_VOLUME_TEXTURE_SIDE};
