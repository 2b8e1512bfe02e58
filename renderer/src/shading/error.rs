//! Errors of building shading data: each names the file and, where it applies, the texel or
//! field and its limit.

use std::path::PathBuf;

/// Why an environment (or other shading data) could not be built.
#[derive(Debug, thiserror::Error)]
pub enum ShadingError {
    /// The image could not be opened or decoded.
    #[error("{file}: cannot read the environment map: {source}")]
    Image {
        /// The file.
        file: PathBuf,
        /// The decoder's error.
        source: image::ImageError,
    },
    /// The map is empty or too large to index and sample.
    #[error(
        "{file}: environment map is {width}x{height} texels; it must hold 1 to {limit} texels"
    )]
    MapSize {
        /// The file.
        file: PathBuf,
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
        /// Largest supported texel count.
        limit: u64,
    },
    /// A texel is negative, infinite or NaN.
    #[error("{file}: texel (column {x}, row {y}) is {value}; environment radiance must be finite and >= 0")]
    Texel {
        /// The file.
        file: PathBuf,
        /// Column.
        x: u32,
        /// Row (0 at the top).
        y: u32,
        /// The offending RGB value.
        value: String,
    },
    /// A parameter is out of its range.
    #[error("{file}: environment {field} is {value}; it must be {limit}")]
    Parameter {
        /// The environment map the parameter belongs to.
        file: PathBuf,
        /// The parameter's name in the scene file.
        field: &'static str,
        /// Its value.
        value: f32,
        /// The range it must lie in.
        limit: &'static str,
    },
    /// Uploading to the device failed.
    #[error("{file}: cannot upload the environment map: {source}")]
    Gpu {
        /// The file (empty for a constant environment).
        file: PathBuf,
        /// The device error.
        source: lazysolid_compute::gpu::GpuError,
    },
}
