//! What a render leaves on disk: the [`Film`] the integrator accumulates into, an HDR OpenEXR
//! that keeps every sample value (and the auxiliary layers a denoiser or a debugger wants), and
//! an 8-bit sRGB PNG for people to look at and for FLIP comparisons.
//!
//! Every writer goes through a temporary file in the destination folder and a rename, so an
//! interrupted or failed write never leaves a truncated image behind under the real name.

mod animation;
mod error;
mod exr_io;
mod film;
mod png_io;
mod tonemap;

pub use animation::{preview_frame, write_gif};
pub use error::OutputError;
pub use exr_io::{read_exr_layer, read_exr_rgb, write_exr};
pub use film::Film;
pub(crate) use lazysolid_compute::atomic_file::write_atomically;
pub(crate) use png_io::write_rgb8;
pub use png_io::{tonemapped_rgb8, write_layer_png, write_png, LayerMapping};
pub(crate) use tonemap::encode8;
pub use tonemap::{srgb_eotf, srgb_oetf, Operator, ToneMap};
