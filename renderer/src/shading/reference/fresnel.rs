//! Fresnel reflectance (twin of `render/fresnel.glsl`).

use glam::Vec3;

/// Unpolarized reflectance at `cos_i` of an interface with `eta = n_t / n_i`; 1 under total
/// internal reflection.
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (s * s + p * p)
}

/// Exact unpolarized reflectance of a conductor of complex index `eta + i kappa` per channel.
pub fn fresnel_conductor(cos_i: f32, eta: Vec3, kappa: Vec3) -> Vec3 {
    let c = cos_i.clamp(0.0, 1.0);
    let channel = |n: f32, k: f32| {
        let c2 = c * c;
        let s2 = 1.0 - c2;
        let (n2, k2) = (n * n, k * k);
        let t0 = n2 - k2 - s2;
        let a2b2 = (t0 * t0 + 4.0 * n2 * k2).sqrt();
        let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
        let t1 = a2b2 + c2;
        let t2 = 2.0 * c * a;
        let rs = (t1 - t2) / (t1 + t2).max(1e-30);
        let t3 = c2 * a2b2 + s2 * s2;
        let t4 = t2 * s2;
        let rp = rs * (t3 - t4) / (t3 + t4).max(1e-30);
        0.5 * (rs + rp)
    };
    Vec3::new(
        channel(eta.x, kappa.x),
        channel(eta.y, kappa.y),
        channel(eta.z, kappa.z),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values() {
        // Normal incidence: ((n - 1) / (n + 1))^2, and ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
        assert!((fresnel_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        assert_eq!(fresnel_dielectric(0.1, 1.0 / 1.5), 1.0);
        let f = fresnel_conductor(1.0, Vec3::splat(0.2), Vec3::splat(3.0));
        let expect = (0.64 + 9.0) / (1.44 + 9.0);
        assert!((f.x - expect).abs() < 1e-5, "{f} vs {expect}");
        // A conductor with k = 0 is a dielectric.
        let f = fresnel_conductor(0.6, Vec3::splat(1.5), Vec3::ZERO);
        assert!((f.x - fresnel_dielectric(0.6, 1.5)).abs() < 1e-5);
        assert!((fresnel_conductor(0.0, Vec3::splat(0.2), Vec3::splat(3.0)).x - 1.0).abs() < 1e-5);
    }
}
