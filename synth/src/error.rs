//! Errors of exemplar loading, analysis and synthesis: each names the file or parameter at
//! fault and the limit it broke.

use lazysolid_compute::gpu::GpuError;
use std::path::PathBuf;

/// Why an exemplar could not be used or a synthesis could not run.
#[derive(Debug, thiserror::Error)]
pub enum SynthError {
    /// The file could not be read at all.
    #[error("{path}: cannot read the exemplar: {source}")]
    Io {
        /// The exemplar file.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// The file is not a decodable image.
    #[error("{path}: cannot decode the exemplar: {reason}")]
    Decode {
        /// The exemplar file.
        path: PathBuf,
        /// What the decoder reported.
        reason: String,
    },
    /// A GIMP pattern header field is out of range.
    #[error("{path}: GIMP pattern header field `{field}` is {value}; {limit}")]
    PatternHeader {
        /// The pattern file.
        path: PathBuf,
        /// The header field (e.g. `magic`, `bytes_per_pixel`).
        field: &'static str,
        /// The value found.
        value: String,
        /// What the field must be.
        limit: String,
    },
    /// The image has an unusable number of channels.
    #[error("{path}: the exemplar has {channels} channel(s); only 1 (grey), 2 (grey+alpha), 3 (RGB) or 4 (RGBA) are supported")]
    Channels {
        /// The exemplar file.
        path: PathBuf,
        /// Channels found.
        channels: u32,
    },
    /// The exemplar is too small for the synthesis pyramid or too large for the analysis.
    #[error("{path}: the exemplar is {width}x{height}; both sides must lie in {min}..={max} pixels (the pyramid needs at least {min}, the analysis allows at most {max}; the commands fit larger images to that, see docs/synthesis.md)")]
    Size {
        /// The exemplar file (or its name when built in memory).
        path: PathBuf,
        /// Width found.
        width: u32,
        /// Height found.
        height: u32,
        /// Smallest side allowed.
        min: u32,
        /// Largest side allowed.
        max: u32,
    },
    /// An image cannot be turned into the exemplar a synthesizer needs (`fit.rs`): too small,
    /// too large to read, or outside what the chosen handling can do.
    #[error("{path}: the image is {width}x{height}; {limit}")]
    Fit {
        /// The image file (or its name when built in memory).
        path: PathBuf,
        /// Width found.
        width: u32,
        /// Height found.
        height: u32,
        /// What the handling needs, and why.
        limit: String,
    },
    /// A synthesis or analysis parameter is out of range.
    #[error("synthesis parameter `{name}` is {value}; {limit}")]
    Parameter {
        /// The parameter.
        name: &'static str,
        /// The value given.
        value: String,
        /// The allowed range.
        limit: String,
    },
    /// The GPU failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
}

/// Shorthand for results of this module.
pub type SynthResult<T> = Result<T, SynthError>;
