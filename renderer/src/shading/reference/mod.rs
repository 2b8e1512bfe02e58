//! A CPU twin of the GLSL shading library (`glsl/include/render/*.glsl`): the same maths in
//! f32, written separately, so that tests can compare the kernels with it input by input and
//! check its statistics (energy conservation, normalized pdfs) quickly on the CPU.

mod bsdf;
mod environment;
mod fresnel;
mod glint;
mod lights;
mod microfacet;
mod rng;
mod sampling;
mod texture;

pub use bsdf::{bsdf_eval, bsdf_has_smooth_lobe, bsdf_pdf, bsdf_sample, BsdfSample};
pub use environment::{env_eval, env_pdf, env_sample, EnvSample};
pub use fresnel::{fresnel_conductor, fresnel_dielectric};
pub use glint::{
    glint_eval, glint_pdf, glint_pndf, glint_sample, glint_shade, GlintParams, GlintShade,
};
pub use lights::{light_intersect, light_pdf, light_sample, LightHit, LightSample};
pub use microfacet::{ggx_d, ggx_g1, ggx_g2, ggx_sample_vndf, ggx_vndf_pdf, GGX_MIN_ALPHA};
pub use rng::{rng_hash, rng_init, rng_next, rng_next2};
pub use sampling::{
    make_frame, pdf_cosine_hemisphere, sample_concentric_disk, sample_cosine_hemisphere,
    sample_uniform_sphere,
};
pub use texture::{solid_texture_albedo, texture_noise};
