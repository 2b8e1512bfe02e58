//! 2D textures read at a surface's texture coordinates: albedo images and tangent-space normal
//! maps, each with its MIP pyramid, uploaded together for the path tracer
//! (`glsl/include/render/image.glsl`) with a CPU twin of the lookup ([`sample`]).

mod error;
mod gpu;
mod pyramid;
pub mod sample;

pub use error::ImageError;
pub use gpu::{
    DeviceImages, GpuImageRecord, GpuVmfRecord, ImageSet, MAX_IMAGE_LEVELS, MAX_VMF_LOBES,
};
pub use pyramid::{ImageEncoding, ImageTexture, MAX_IMAGE_EDGE, MAX_IMAGE_TEXELS};
