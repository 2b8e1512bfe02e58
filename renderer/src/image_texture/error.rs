//! Why an image texture could not be made: each message names the file and the limit.

use std::path::PathBuf;

/// An image that cannot serve as a texture.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The file could not be read or decoded.
    #[error("{file}: cannot read the image: {problem}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The decoder's description.
        problem: String,
    },
    /// An edge outside 1..=`max` texels.
    #[error("{file}: the image is {width}×{height}; each edge must be 1 to {max} texels")]
    Size {
        /// The file.
        file: PathBuf,
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
        /// The largest edge.
        max: u32,
    },
    /// The images of one scene hold more texels (all levels) than one device buffer may.
    #[error("the scene's images hold {texels} texels with their MIP levels; at most {max} fit one device buffer")]
    Total {
        /// Texels of every level of every image.
        texels: u64,
        /// The limit.
        max: u64,
    },
}
