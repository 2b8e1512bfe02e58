//! The plastic coat's precomputed terms (`plastic_*` in `glsl/include/render/bsdf.glsl`): its
//! directional albedo E(cos θ) at the table's knots and the share F_in of the base's diffuse
//! light that it reflects back down. The kernel only interpolates them, because E of a rough
//! coat is an integral over the GGX lobe that a shading call cannot afford.
//!
//! The diffuse part of the plastic divides by 1 − ρ·F_in with F_in = 1 − (1/η²)∫(1 − E)2μ dμ
//! taken over the same E the kernel reads, so a white base returns exactly what the coat does
//! not reflect, whatever the table's error.

use super::reference::{fresnel_dielectric, ggx_g1, ggx_g2, ggx_sample_vndf, GGX_MIN_ALPHA};
use crate::shader_constants::PLASTIC_COAT_KNOTS;
use glam::{Vec2, Vec3};

/// Knots of the coat table.
pub const COAT_KNOTS: usize = PLASTIC_COAT_KNOTS as usize;

/// Strata per axis of the quadrature of a rough coat's albedo at one knot.
const ALBEDO_STRATA: usize = 48;
/// Midpoint intervals of the cosine-weighted integral of the table.
const INTERNAL_INTERVALS: usize = 2048;

/// A coat's precomputed terms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoatTerms {
    /// E(cos θ) at cos θ = (i / (knots − 1))².
    pub albedo: [f32; COAT_KNOTS],
    /// F_in: reflectance of the coat's inner side to the base's diffuse light.
    pub internal: f32,
}

/// E(cos θ) from the table, linear in √cos θ between knots (the kernel's interpolation).
pub fn coat_albedo_at(table: &[f32; COAT_KNOTS], cos_theta: f32) -> f32 {
    let last = COAT_KNOTS - 1;
    let x = cos_theta.clamp(0.0, 1.0).sqrt() * last as f32;
    let i = (x as usize).min(last - 1);
    let (a, b) = (table[i], table[i + 1]);
    a + (b - a) * (x - i as f32)
}

/// The terms of a coat of index `ior` (> 1) and GGX `roughness` (α = roughness²; below
/// `GGX_MIN_ALPHA` the coat is smooth and the kernel uses the exact Fresnel reflectance).
pub fn coat_terms(roughness: f32, ior: f32) -> CoatTerms {
    let alpha = roughness * roughness;
    let smooth = alpha < GGX_MIN_ALPHA;
    let mut albedo = [0.0; COAT_KNOTS];
    for (i, e) in albedo.iter_mut().enumerate() {
        let x = i as f32 / (COAT_KNOTS - 1) as f32;
        let cos = x * x;
        *e = if smooth {
            fresnel_dielectric(cos, ior)
        } else {
            rough_albedo(cos, alpha, ior)
        };
    }
    let eta2 = (ior as f64) * (ior as f64);
    let internal = if smooth {
        1.0 - (1.0 - fresnel_diffuse_reflectance(ior as f64)) / eta2
    } else {
        let h = 1.0 / INTERNAL_INTERVALS as f64;
        let escaping: f64 = (0..INTERNAL_INTERVALS)
            .map(|k| {
                let mu = (k as f64 + 0.5) * h;
                (1.0 - coat_albedo_at(&albedo, mu as f32) as f64) * 2.0 * mu * h
            })
            .sum();
        1.0 - escaping / eta2
    };
    CoatTerms {
        albedo,
        internal: internal as f32,
    }
}

/// Single-scattering reflectance of a GGX dielectric interface seen at `cos_theta`: the mean
/// of F(wo·h)·G2/G1 over visible normals, on a stratified grid (deterministic).
fn rough_albedo(cos_theta: f32, alpha: f32, ior: f32) -> f32 {
    // At grazing incidence the integrand's limit is approached from a hair above the horizon.
    let c = cos_theta.max(1e-3);
    let wo = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
    let n = ALBEDO_STRATA;
    let mut sum = 0.0f64;
    for k in 0..n * n {
        let u = Vec2::new(
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / n as f32,
        );
        let h = ggx_sample_vndf(wo, alpha, u);
        let d = wo.dot(h);
        let wi = 2.0 * d * h - wo;
        if d > 0.0 && wi.z > 0.0 {
            let g = ggx_g2(wo, wi, alpha) / ggx_g1(wo, alpha);
            sum += (fresnel_dielectric(d, ior) * g) as f64;
        }
    }
    (sum / (n * n) as f64) as f32
}

/// Hemispherical (cosine-weighted) reflectance 2∫F(μ)μ dμ of a smooth interface entered from
/// the side of index 1 into index `n` > 1, in closed form (the unpolarized average of the
/// s and p integrals, as in Walsh's and Stern's formulas).
fn fresnel_diffuse_reflectance(n: f64) -> f64 {
    let n2 = n * n;
    let n4 = n2 * n2;
    0.5 + (n - 1.0) * (3.0 * n + 1.0) / (6.0 * (n + 1.0).powi(2))
        + n2 * (n2 - 1.0).powi(2) / (n2 + 1.0).powi(3) * ((n - 1.0) / (n + 1.0)).ln()
        - 2.0 * n * n2 * (n2 + 2.0 * n - 1.0) / ((n2 + 1.0) * (n4 - 1.0))
        + 8.0 * n4 * (n4 + 1.0) / ((n2 + 1.0) * (n4 - 1.0).powi(2)) * n.ln()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2∫F(μ)μ dμ by the midpoint rule, for the closed form to be held to.
    fn numeric_diffuse_reflectance(n: f32) -> f64 {
        let k = 20_000;
        (0..k)
            .map(|i| {
                let mu = (i as f64 + 0.5) / k as f64;
                fresnel_dielectric(mu as f32, n) as f64 * 2.0 * mu / k as f64
            })
            .sum()
    }

    #[test]
    fn closed_form_diffuse_reflectance_matches_the_integral() {
        for n in [1.05f32, 1.33, 1.5, 2.0, 2.5, 4.0] {
            let closed = fresnel_diffuse_reflectance(n as f64);
            let numeric = numeric_diffuse_reflectance(n);
            assert!(
                (closed - numeric).abs() < 1e-5,
                "n {n}: {closed} vs {numeric}"
            );
        }
        // The textbook value for glass: 9.2 % of diffuse light reflected from outside.
        assert!((fresnel_diffuse_reflectance(1.5) - 0.0918).abs() < 1e-4);
    }

    #[test]
    fn smooth_coat_terms_are_fresnel_and_rough_ones_approach_them() {
        let smooth = coat_terms(0.0, 1.5);
        assert_eq!(smooth.albedo[COAT_KNOTS - 1], fresnel_dielectric(1.0, 1.5));
        // 1 − (1 − 0.0918)/2.25: the inner side of glass reflects 60 % of diffuse light.
        assert!(
            (smooth.internal - 0.5964).abs() < 1e-3,
            "{}",
            smooth.internal
        );
        let rough = coat_terms(0.1, 1.5);
        for (i, (r, s)) in rough.albedo.iter().zip(&smooth.albedo).enumerate().skip(6) {
            assert!((r - s).abs() < 0.01, "knot {i}: rough {r} smooth {s}");
        }
        assert!((rough.internal - smooth.internal).abs() < 0.01);
        // Rougher coats reflect less at grazing incidence (masking) and pass more to the base.
        let rougher = coat_terms(0.5, 1.5);
        assert!(rougher.albedo[1] < rough.albedo[1]);
        assert!(rougher.internal < rough.internal);
    }
}
