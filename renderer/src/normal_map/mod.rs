//! Normal-map filtering by mixtures of von Mises–Fisher lobes (seed 000 ch. 7, Han et al.
//! 2007): the lobe and its closed forms ([`vmf`]) and the spherical EM fit of a texel's
//! normals with importance sampling of the result ([`mixture`]), and the MIP pyramid of a
//! normal map as mixtures beside the plain MIP of averaged normals ([`pyramid`]) and the
//! linear nine-coefficient SH distribution that Lambertian shading needs ([`sh`]). CPU
//! reference; what renders with it comes with the normal-map material.

pub mod gpu_fit;
pub mod mixture;
pub mod pyramid;
pub mod sh;
pub mod vmf;
