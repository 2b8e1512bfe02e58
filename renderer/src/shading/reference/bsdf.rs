//! BSDFs in the local shading frame (twin of `render/bsdf.glsl`, whose header states the
//! conventions: two-sided opaque materials, dielectrics that read wo.z's sign, weights
//! f·|cos θi| / pdf, no 1/η² radiance scaling).

use super::fresnel::{fresnel_conductor, fresnel_dielectric};
use super::microfacet::{ggx_d, ggx_g1, ggx_g2, ggx_sample_vndf, GGX_MIN_ALPHA};
use super::sampling::{pdf_cosine_hemisphere, sample_cosine_hemisphere};
use crate::shader_constants::{
    MATERIAL_CONDUCTOR, MATERIAL_DIELECTRIC, MATERIAL_LAMBERTIAN, MATERIAL_PLASTIC,
};
use crate::shading::{coat_albedo_at, GpuMaterial};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// A sampled direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Direction, local frame.
    pub wi: Vec3,
    /// f·|cos θi| / pdf.
    pub weight: Vec3,
    /// Solid-angle pdf, or the lobe probability of a delta sample.
    pub pdf: f32,
    /// A delta lobe was sampled.
    pub specular: bool,
}

/// The scattering model of a material, with the side of the surface resolved.
enum Model {
    Lambertian,
    Conductor { alpha: Option<f32> },
    Plastic { alpha: Option<f32> },
    Dielectric { alpha: Option<f32>, eta: f32 },
    Black,
}

/// The material's model seen from `wo`, and the z sign that brings wo to +z.
fn model(m: &GpuMaterial, wo: Vec3) -> (Model, f32) {
    let a = m.roughness * m.roughness;
    let alpha = (a >= GGX_MIN_ALPHA).then_some(a);
    let side = if wo.z < 0.0 { -1.0 } else { 1.0 };
    let model = match m.kind {
        MATERIAL_LAMBERTIAN => Model::Lambertian,
        MATERIAL_CONDUCTOR => Model::Conductor { alpha },
        MATERIAL_PLASTIC => Model::Plastic { alpha },
        MATERIAL_DIELECTRIC => Model::Dielectric {
            alpha,
            eta: if side > 0.0 { m.ior } else { 1.0 / m.ior },
        },
        _ => Model::Black,
    };
    (model, side)
}

fn flip(v: Vec3, side: f32) -> Vec3 {
    Vec3::new(v.x, v.y, v.z * side)
}

fn mirror(wo: Vec3) -> Vec3 {
    Vec3::new(-wo.x, -wo.y, wo.z)
}

fn reflect(wo: Vec3, h: Vec3) -> Vec3 {
    2.0 * wo.dot(h) * h - wo
}

/// Refraction of `wo` through `n` (wo·n > 0), `eta = n_t / n_i`; None under TIR.
fn refract(wo: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let c = wo.dot(n);
    let s2 = (1.0 - c * c).max(0.0) / (eta * eta);
    if s2 >= 1.0 {
        return None;
    }
    Some(-wo / eta + (c / eta - (1.0 - s2).sqrt()) * n)
}

/// Directional albedo of a plastic's coat at `cos_theta`: Fresnel when smooth, else the table.
fn plastic_coat_albedo(m: &GpuMaterial, alpha: Option<f32>, cos_theta: f32) -> f32 {
    match alpha {
        None => fresnel_dielectric(cos_theta, m.ior),
        Some(_) => coat_albedo_at(&m.coat_albedo, cos_theta),
    }
}

fn plastic_specular_probability(coat: f32, albedo: Vec3) -> f32 {
    let d = (1.0 - coat) * (albedo.x + albedo.y + albedo.z) * (1.0 / 3.0);
    let s = coat + d;
    if s > 0.0 {
        coat / s
    } else {
        1.0
    }
}

/// Microfacet reflection term D·G2/(4 cos θo) at the half vector of (wo, wi), both above.
fn reflection_lobe(wo: Vec3, wi: Vec3, alpha: f32) -> (Vec3, f32) {
    let h = (wo + wi).normalize();
    (h, ggx_d(h, alpha) * ggx_g2(wo, wi, alpha) / (4.0 * wo.z))
}

/// Density of reflecting through a visible normal: G1·D/(4 cos θo).
fn reflection_pdf(wo: Vec3, h: Vec3, alpha: f32) -> f32 {
    ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0 * wo.z)
}

/// The refraction half vector on wo's side, when (wo, wi) is a refraction pair.
fn refraction_half_vector(wo: Vec3, wi: Vec3, eta: f32) -> Option<Vec3> {
    let v = wo + eta * wi;
    let len2 = v.dot(v);
    if len2 <= 0.0 {
        return None;
    }
    let mut h = v / len2.sqrt();
    if h.z < 0.0 {
        h = -h;
    }
    (wo.dot(h) > 0.0 && wi.dot(h) < 0.0).then_some(h)
}

/// (f·|cos θi|, pdf) of the non-delta lobes for wo.z > 0.
fn eval_pdf(m: &GpuMaterial, model: &Model, albedo: Vec3, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
    match *model {
        Model::Lambertian => {
            if wi.z > 0.0 {
                (albedo * (wi.z * FRAC_1_PI), pdf_cosine_hemisphere(wi.z))
            } else {
                (Vec3::ZERO, 0.0)
            }
        }
        Model::Conductor { alpha } => match alpha {
            Some(alpha) if wi.z > 0.0 => {
                let (h, lobe) = reflection_lobe(wo, wi, alpha);
                let f = fresnel_conductor(wo.dot(h), m.color.into(), m.k.into());
                (f * lobe, reflection_pdf(wo, h, alpha))
            }
            _ => (Vec3::ZERO, 0.0),
        },
        Model::Plastic { alpha } => {
            if wi.z <= 0.0 {
                return (Vec3::ZERO, 0.0);
            }
            let coat = plastic_coat_albedo(m, alpha, wo.z);
            let (to, ti) = (1.0 - coat, 1.0 - plastic_coat_albedo(m, alpha, wi.z));
            let p = plastic_specular_probability(coat, albedo);
            // Light that crosses the coat, meets the base and leaves after any number of
            // reflections under the coat (see render/bsdf.glsl).
            let mut f = albedo * (to * ti * wi.z * FRAC_1_PI / (m.ior * m.ior))
                / (Vec3::ONE - albedo * m.coat_internal);
            let mut pdf = (1.0 - p) * wi.z * FRAC_1_PI;
            if let Some(alpha) = alpha {
                let (h, lobe) = reflection_lobe(wo, wi, alpha);
                f += Vec3::splat(fresnel_dielectric(wo.dot(h), m.ior) * lobe);
                pdf += p * reflection_pdf(wo, h, alpha);
            }
            (f, pdf)
        }
        Model::Dielectric {
            alpha: Some(alpha),
            eta,
        } => {
            if wi.z > 0.0 {
                let (h, lobe) = reflection_lobe(wo, wi, alpha);
                let f = fresnel_dielectric(wo.dot(h), eta);
                return (Vec3::splat(f * lobe), f * reflection_pdf(wo, h, alpha));
            }
            if wi.z == 0.0 {
                return (Vec3::ZERO, 0.0);
            }
            let Some(h) = refraction_half_vector(wo, wi, eta) else {
                return (Vec3::ZERO, 0.0);
            };
            let (c, ci) = (wo.dot(h), wi.dot(h));
            let denom = c + eta * ci;
            let t = 1.0 - fresnel_dielectric(c, eta);
            let d = ggx_d(h, alpha);
            // dω_h/dω_i of refraction (Walter et al. 2007).
            let jacobian = eta * eta * (-ci) / (denom * denom);
            let f = t * d * ggx_g2(wo, wi, alpha) * c * jacobian / wo.z;
            let pdf = t * ggx_g1(wo, alpha) * c * d / wo.z * jacobian;
            (albedo * f, pdf)
        }
        Model::Dielectric { alpha: None, .. } | Model::Black => (Vec3::ZERO, 0.0),
    }
}

/// f(wo, wi)·|cos θi| of the non-delta lobes. `albedo` is the textured colour (lambertian and
/// plastic albedo, dielectric tint); a conductor reads η and κ from the material.
pub fn bsdf_eval(m: &GpuMaterial, albedo: Vec3, wo: Vec3, wi: Vec3) -> Vec3 {
    if wo.z == 0.0 {
        return Vec3::ZERO;
    }
    let (model, side) = model(m, wo);
    eval_pdf(m, &model, albedo, flip(wo, side), flip(wi, side)).0
}

/// Solid-angle density with which [`bsdf_sample`] produces `wi` through non-delta lobes.
pub fn bsdf_pdf(m: &GpuMaterial, albedo: Vec3, wo: Vec3, wi: Vec3) -> f32 {
    if wo.z == 0.0 {
        return 0.0;
    }
    let (model, side) = model(m, wo);
    eval_pdf(m, &model, albedo, flip(wo, side), flip(wi, side)).1
}

/// True when the material has a non-delta lobe (next-event estimation is useful).
pub fn bsdf_has_smooth_lobe(m: &GpuMaterial) -> bool {
    match model(m, Vec3::Z).0 {
        Model::Lambertian | Model::Plastic { .. } => true,
        Model::Conductor { alpha } | Model::Dielectric { alpha, .. } => alpha.is_some(),
        Model::Black => false,
    }
}

/// Samples a direction with `u` in [0, 1)³ (`u.z` picks the lobe); None when absorbed.
pub fn bsdf_sample(m: &GpuMaterial, albedo: Vec3, wo: Vec3, u: Vec3) -> Option<BsdfSample> {
    if wo.z == 0.0 {
        return None;
    }
    let (model, side) = model(m, wo);
    let wo = flip(wo, side);
    let uv = Vec2::new(u.x, u.y);
    let delta = |wi: Vec3, weight: Vec3, pdf: f32| BsdfSample {
        wi: flip(wi, side),
        weight,
        pdf,
        specular: true,
    };
    // A non-delta direction: weight and pdf from the lobes themselves.
    let smooth = |wi: Vec3| -> Option<BsdfSample> {
        let (f, pdf) = eval_pdf(m, &model, albedo, wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi: flip(wi, side),
            weight: f / pdf,
            pdf,
            specular: false,
        })
    };
    match model {
        Model::Lambertian => {
            let wi = sample_cosine_hemisphere(uv);
            let pdf = pdf_cosine_hemisphere(wi.z);
            (pdf > 0.0).then(|| BsdfSample {
                wi: flip(wi, side),
                weight: albedo,
                pdf,
                specular: false,
            })
        }
        Model::Conductor { alpha: None } => Some(delta(
            mirror(wo),
            fresnel_conductor(wo.z, m.color.into(), m.k.into()),
            1.0,
        )),
        Model::Conductor { alpha: Some(alpha) } => {
            let h = ggx_sample_vndf(wo, alpha, uv);
            let c = wo.dot(h);
            let wi = reflect(wo, h);
            if c <= 0.0 || wi.z <= 0.0 {
                return None;
            }
            let weight = fresnel_conductor(c, m.color.into(), m.k.into())
                * (ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha));
            let pdf = eval_pdf(m, &model, albedo, wo, wi).1;
            (pdf > 0.0).then(|| BsdfSample {
                wi: flip(wi, side),
                weight,
                pdf,
                specular: false,
            })
        }
        Model::Plastic { alpha } => {
            let coat = plastic_coat_albedo(m, alpha, wo.z);
            let p = plastic_specular_probability(coat, albedo);
            let wi = if u.z < p {
                match alpha {
                    None => return Some(delta(mirror(wo), Vec3::splat(coat / p), p)),
                    Some(alpha) => reflect(wo, ggx_sample_vndf(wo, alpha, uv)),
                }
            } else {
                sample_cosine_hemisphere(uv)
            };
            if wi.z <= 0.0 {
                return None;
            }
            smooth(wi)
        }
        Model::Dielectric { alpha: None, eta } => {
            let f = fresnel_dielectric(wo.z, eta);
            if u.z < f {
                Some(delta(mirror(wo), Vec3::ONE, f))
            } else {
                refract(wo, Vec3::Z, eta).map(|wi| delta(wi, albedo, 1.0 - f))
            }
        }
        Model::Dielectric {
            alpha: Some(alpha),
            eta,
        } => {
            let h = ggx_sample_vndf(wo, alpha, uv);
            let c = wo.dot(h);
            if c <= 0.0 {
                return None;
            }
            let f = fresnel_dielectric(c, eta);
            let (wi, tint) = if u.z < f {
                let wi = reflect(wo, h);
                if wi.z <= 0.0 {
                    return None;
                }
                (wi, Vec3::ONE)
            } else {
                let wi = refract(wo, h, eta)?;
                if wi.z >= 0.0 {
                    return None;
                }
                (wi, albedo)
            };
            let weight = tint * (ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha));
            let pdf = eval_pdf(m, &model, albedo, wo, wi).1;
            (pdf > 0.0).then(|| BsdfSample {
                wi: flip(wi, side),
                weight,
                pdf,
                specular: false,
            })
        }
        Model::Black => None,
    }
}
