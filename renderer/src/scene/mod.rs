//! Scenes: the resolved scene types and (as it lands) the TOML scene loader.

mod types;

pub use types::*;
