//! The spherical-harmonics normal distribution of a normal map (seed 000 ch. 7, Algorithm A):
//! per texel the nine real SH coefficients (bands 0–2) of its normals' distribution, which are
//! *linear* in the normals, so MIP levels average them with no fitting. Nine coefficients
//! suffice for Lambertian shading (T:3081–3083); the vMF mixtures ([`super::pyramid`]) are what
//! sharper lobes need.

use crate::glint::NormalExample;
use glam::DVec3;
use std::f64::consts::PI;

/// Coefficients per texel: bands 0, 1 and 2.
pub const SH_COEFFICIENTS: usize = 9;

/// The real SH basis of bands 0–2 at unit direction `n` (order: l = 0; l = 1, m = −1, 0, 1;
/// l = 2, m = −2 … 2).
pub fn sh9(n: DVec3) -> [f64; SH_COEFFICIENTS] {
    let (x, y, z) = (n.x, n.y, n.z);
    [
        0.282_094_791_773_878,
        0.488_602_511_902_920 * y,
        0.488_602_511_902_920 * z,
        0.488_602_511_902_920 * x,
        1.092_548_430_592_079 * x * y,
        1.092_548_430_592_079 * y * z,
        0.315_391_565_252_520 * (3.0 * z * z - 1.0),
        1.092_548_430_592_079 * x * z,
        0.546_274_215_296_040 * (x * x - y * y),
    ]
}

/// The clamped cosine's band weights `Â_l = 2π ∫₀¹ t P_l(t) dt` (π, 2π/3, π/4): by Funk–Hecke
/// the Lambertian response of a distribution with coefficients `γ_lm` is `Σ Â_l γ_lm Y_lm(ω)`.
const LAMBERT_BANDS: [f64; 3] = [PI, 2.0 * PI / 3.0, PI / 4.0];

/// `∫ max(ω·n, 0) γ(n) dn` up to band 2, for the distribution with coefficients `c`: the mean
/// clamped cosine between `omega` and the normals a texel covers (Eq. 7.12 with l* = 2).
pub fn lambert_response(c: &[f64; SH_COEFFICIENTS], omega: DVec3) -> f64 {
    let y = sh9(omega);
    (0..SH_COEFFICIENTS)
        .map(|i| {
            let band = if i == 0 {
                0
            } else if i < 4 {
                1
            } else {
                2
            };
            LAMBERT_BANDS[band] * c[i] * y[i]
        })
        .sum()
}

/// Every MIP level of a map's SH coefficients, finest first, each level the 2×2 mean of the one
/// below.
pub fn sh_levels(map: &NormalExample) -> Vec<Vec<[f64; SH_COEFFICIENTS]>> {
    let mut edge = map.size();
    let mut levels = vec![map
        .texels()
        .iter()
        .map(|&n| sh9(super::pyramid::texel_normal(n)))
        .collect::<Vec<_>>()];
    while edge > 1 {
        let half = edge / 2;
        let below = levels.last().expect("one level");
        let level = (0..half * half)
            .map(|t| {
                let (x, y) = (t % half, t / half);
                let quad = [
                    below[2 * y * edge + 2 * x],
                    below[2 * y * edge + 2 * x + 1],
                    below[(2 * y + 1) * edge + 2 * x],
                    below[(2 * y + 1) * edge + 2 * x + 1],
                ];
                std::array::from_fn(|i| quad.iter().map(|q| q[i]).sum::<f64>() / 4.0)
            })
            .collect();
        levels.push(level);
        edge = half;
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    fn bumpy(size: usize) -> NormalExample {
        let texels = (0..size * size)
            .map(|i| {
                let (x, y) = ((i % size) as f32, (i / size) as f32);
                Vec2::new(0.5 * (x * 0.9).sin(), 0.45 * (y * 1.3 + x * 0.2).cos())
            })
            .collect();
        NormalExample::from_normals("bumpy", size, texels).unwrap()
    }

    /// Linearity: each level's coefficients equal the basis averaged directly over the texel's
    /// footprint of fine normals.
    #[test]
    fn mip_levels_are_the_footprint_means_of_the_basis() {
        let map = bumpy(16);
        let levels = sh_levels(&map);
        assert_eq!(levels.len(), 5);
        for (k, level) in levels.iter().enumerate() {
            let span = 1usize << k;
            let edge = 16 >> k;
            for (t, texel) in level.iter().enumerate() {
                let (tx, ty) = (t % edge, t / edge);
                let mut direct = [0.0; SH_COEFFICIENTS];
                for i in 0..span * span {
                    let n = map.texel(tx * span + i % span, ty * span + i / span);
                    let y = sh9(super::super::pyramid::texel_normal(n));
                    direct.iter_mut().zip(y).for_each(|(d, v)| *d += v);
                }
                for (i, (&got, sum)) in texel.iter().zip(direct).enumerate() {
                    let want = sum / (span * span) as f64;
                    assert!((got - want).abs() < 1e-12, "level {k}, texel {t}, {i}");
                }
            }
        }
    }

    /// The basis is orthonormal (checked by quadrature over the sphere) and the band-2
    /// Lambertian response matches the brute-force mean clamped cosine within the truncation
    /// error of bands 4 and up. That error is at most 0.074 for a single normal, the worst case,
    /// on the unit scale of the cosine, and 0.014 for the coarsest level of a bumpy map, which
    /// averaging smooths; the bounds below sit above these.
    #[test]
    fn lambert_response_matches_the_brute_force_mean_to_truncation_error() {
        // Orthonormality on a (cos θ, φ) midpoint grid.
        let (nt, np) = (200usize, 400usize);
        let mut gram = [[0.0f64; SH_COEFFICIENTS]; SH_COEFFICIENTS];
        for a in 0..nt {
            let z = -1.0 + 2.0 * (a as f64 + 0.5) / nt as f64;
            let s = (1.0 - z * z).sqrt();
            for b in 0..np {
                let phi = 2.0 * PI * (b as f64 + 0.5) / np as f64;
                let y = sh9(DVec3::new(s * phi.cos(), s * phi.sin(), z));
                for i in 0..SH_COEFFICIENTS {
                    for j in 0..SH_COEFFICIENTS {
                        gram[i][j] += y[i] * y[j] * 4.0 * PI / (nt * np) as f64;
                    }
                }
            }
        }
        for (i, row) in gram.iter().enumerate() {
            for (j, &g) in row.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((g - want).abs() < 1e-3, "⟨Y{i}, Y{j}⟩ = {g}");
            }
        }
        let map = bumpy(16);
        let levels = sh_levels(&map);
        let normals: Vec<DVec3> = map
            .texels()
            .iter()
            .map(|&n| super::super::pyramid::texel_normal(n))
            .collect();
        let mut worst_single = 0.0f64;
        let mut worst_mean = 0.0f64;
        for a in 0..24 {
            for b in 0..48 {
                let z = -1.0 + 2.0 * (a as f64 + 0.5) / 24.0;
                let s = (1.0 - z * z).sqrt();
                let phi = 2.0 * PI * (b as f64 + 0.5) / 48.0;
                let omega = DVec3::new(s * phi.cos(), s * phi.sin(), z);
                let brute = normals.iter().map(|n| n.dot(omega).max(0.0)).sum::<f64>()
                    / normals.len() as f64;
                worst_mean = worst_mean.max((lambert_response(&levels[4][0], omega) - brute).abs());
                let single = sh9(DVec3::Z);
                worst_single =
                    worst_single.max((lambert_response(&single, omega) - omega.z.max(0.0)).abs());
            }
        }
        assert!(worst_single < 0.075, "single normal: {worst_single}");
        assert!(worst_mean < 0.02, "coarsest level: {worst_mean}");
        assert!(worst_mean < worst_single, "averaging smooths the response");
    }
}
