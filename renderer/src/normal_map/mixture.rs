//! Mixtures of von Mises–Fisher lobes fitted to the normals a texel covers by spherical EM
//! (seed 000 Algorithm 7.1, Banerjee et al. 2005), and drawn from for importance sampling.
//!
//! **The E-step keeps the weights.** The thesis prints `<z_ij> = γ_j(n_i) / Σ_k γ_k(n_i)`
//! without `α_j`; the standard movMF E-step, used here, is `α_j γ_j / Σ_k α_k γ_k`. Without the
//! weights a lobe that explains a few normals pulls as hard as one that explains most.
//!
//! **Initialization** (T:3436–3448): the lobes start on the `J` normals farthest apart
//! (Hochbaum–Shmoys: the first normal, then repeatedly the one farthest from all chosen), each
//! sharp; at coarser MIP levels the caller passes its children's lobes instead.

use super::vmf::{kappa_from_length, VmfLobe, MAX_KAPPA};
use glam::DVec3;

/// Iterations after which the fit stops even if it still moves: the thesis "seldom needs more
/// than 10".
pub const MAX_EM_ITERATIONS: u32 = crate::shader_constants::VMF_EM_MAX_ITERATIONS;

/// Change of the mean log-likelihood per normal under which the fit has converged.
pub const EM_TOLERANCE: f64 = 1e-7;

/// Concentration the initial lobes get: sharp (the thesis: "κ to a large initial value"), yet
/// wide enough that every normal has a non-zero responsibility in double precision.
pub const INITIAL_KAPPA: f64 = 200.0;

/// A weighted set of lobes whose weights sum to 1.
#[derive(Clone, Debug, PartialEq)]
pub struct VmfMixture {
    /// The lobes.
    pub lobes: Vec<VmfLobe>,
}

/// What a fit did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitReport {
    /// EM iterations run.
    pub iterations: u32,
    /// Mean log-likelihood of the normals under the final mixture.
    pub log_likelihood: f64,
}

impl VmfMixture {
    /// The mixture's density at unit direction `n`.
    pub fn density(&self, n: DVec3) -> f64 {
        self.lobes.iter().map(|l| l.alpha * l.density(n)).sum()
    }

    /// A direction drawn from the mixture: `u.0` picks the lobe by its weight and is reused,
    /// rescaled, for the lobe's cosine; `u.1` is the azimuth.
    pub fn sample(&self, u: (f64, f64)) -> DVec3 {
        let mut rest = u.0;
        for (j, lobe) in self.lobes.iter().enumerate() {
            if rest < lobe.alpha || j + 1 == self.lobes.len() {
                let v = (rest / lobe.alpha.max(f64::MIN_POSITIVE)).clamp(0.0, 1.0 - f64::EPSILON);
                return lobe.sample((v, u.1));
            }
            rest -= lobe.alpha;
        }
        DVec3::Z
    }

    /// The number of lobes that stand for distinct directions: lobes of weight above
    /// `min_alpha`, counted once when their means lie within `angle` radians of a counted one.
    pub fn distinct_lobes(&self, angle: f64, min_alpha: f64) -> usize {
        let mut kept: Vec<DVec3> = Vec::new();
        let mut lobes: Vec<&VmfLobe> = self.lobes.iter().filter(|l| l.alpha > min_alpha).collect();
        lobes.sort_by(|a, b| b.alpha.total_cmp(&a.alpha));
        for l in lobes {
            if kept
                .iter()
                .all(|k| k.dot(l.mu).clamp(-1.0, 1.0).acos() > angle)
            {
                kept.push(l.mu);
            }
        }
        kept.len()
    }
}

/// The `j` normals farthest apart (the first normal, then repeatedly the one whose nearest
/// chosen normal is farthest), as sharp lobes of equal weight. A texel with fewer distinct
/// normals than `j` gets repeated lobes, which EM moves together.
pub fn farthest_lobes(normals: &[DVec3], j: usize) -> Vec<VmfLobe> {
    let mut chosen: Vec<DVec3> = Vec::with_capacity(j);
    if normals.is_empty() || j == 0 {
        return Vec::new();
    }
    chosen.push(normals[0]);
    let mut nearest: Vec<f64> = normals.iter().map(|n| n.dot(normals[0])).collect();
    while chosen.len() < j {
        // The largest angle to the nearest chosen is the smallest cosine.
        let (far, _) = nearest
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("normals is not empty");
        let next = normals[far];
        chosen.push(next);
        for (c, n) in nearest.iter_mut().zip(normals) {
            *c = c.max(n.dot(next));
        }
    }
    let alpha = 1.0 / j as f64;
    chosen
        .into_iter()
        .map(|mu| VmfLobe::new(alpha, mu, INITIAL_KAPPA))
        .collect()
}

/// Fits a mixture to unit `normals` (each of weight `weights[i]`, or 1) by spherical EM from
/// the lobes `init`, until the mean log-likelihood moves less than [`EM_TOLERANCE`] or after
/// [`MAX_EM_ITERATIONS`].
///
/// # Panics
/// When `init` is empty or `weights` has another length than `normals` (caller errors).
pub fn fit(
    normals: &[DVec3],
    weights: Option<&[f64]>,
    init: &[VmfLobe],
) -> (VmfMixture, FitReport) {
    assert!(!init.is_empty(), "a mixture needs at least one lobe");
    if let Some(w) = weights {
        assert_eq!(w.len(), normals.len(), "one weight per normal");
    }
    let weight = |i: usize| weights.map_or(1.0, |w| w[i]);
    let total: f64 = (0..normals.len()).map(weight).sum();
    let mut lobes = init.to_vec();
    let mut resp = vec![0.0f64; lobes.len()];
    let mut previous = f64::NEG_INFINITY;
    let mut report = FitReport {
        iterations: 0,
        log_likelihood: f64::NEG_INFINITY,
    };
    if normals.is_empty() || total <= 0.0 {
        return (VmfMixture { lobes }, report);
    }
    for iteration in 1..=MAX_EM_ITERATIONS {
        let mut mass = vec![0.0f64; lobes.len()];
        let mut sum = vec![DVec3::ZERO; lobes.len()];
        let mut log_likelihood = 0.0;
        for (i, &n) in normals.iter().enumerate() {
            // E-step with the weights (module docs).
            let mut norm = 0.0;
            for (r, l) in resp.iter_mut().zip(&lobes) {
                *r = l.alpha * l.density(n);
                norm += *r;
            }
            if norm <= 0.0 {
                // Every lobe too sharp to reach n: give it to the nearest lobe.
                let nearest = (0..lobes.len())
                    .max_by(|&a, &b| lobes[a].mu.dot(n).total_cmp(&lobes[b].mu.dot(n)))
                    .expect("lobes is not empty");
                resp.iter_mut().for_each(|r| *r = 0.0);
                resp[nearest] = 1.0;
                norm = 1.0;
                log_likelihood += weight(i) * f64::MIN_POSITIVE.ln();
            } else {
                log_likelihood += weight(i) * norm.ln();
            }
            for j in 0..lobes.len() {
                let z = weight(i) * resp[j] / norm;
                mass[j] += z;
                sum[j] += n * z;
            }
        }
        // M-step: α from the responsibilities, μ and κ from the mean normal r.
        for j in 0..lobes.len() {
            if mass[j] <= 0.0 {
                lobes[j].alpha = 0.0;
                continue;
            }
            let r = sum[j] / mass[j];
            let len = r.length();
            lobes[j] = VmfLobe {
                alpha: mass[j] / total,
                mu: if len > 0.0 { r / len } else { lobes[j].mu },
                kappa: kappa_from_length(len).min(MAX_KAPPA),
            };
        }
        let mean = log_likelihood / total;
        report = FitReport {
            iterations: iteration,
            log_likelihood: mean,
        };
        if (mean - previous).abs() < EM_TOLERANCE {
            break;
        }
        previous = mean;
    }
    (VmfMixture { lobes }, report)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Normals of a V-groove texel: half tilted by +θ about y, half by −θ, each with a little
    /// deterministic jitter so the lobes have a finite width.
    fn groove(theta: f64, count: usize) -> Vec<DVec3> {
        (0..count)
            .map(|i| {
                let side = if i % 2 == 0 { 1.0 } else { -1.0 };
                let jitter = 0.01 * (((i * 7919) % 101) as f64 / 50.0 - 1.0);
                let a = side * theta + jitter;
                DVec3::new(
                    a.sin(),
                    0.01 * (((i * 104_729) % 97) as f64 / 48.0 - 1.0),
                    a.cos(),
                )
                .normalize()
            })
            .collect()
    }

    #[test]
    fn em_recovers_two_lobes_for_a_v_groove_and_one_for_a_flat_texel() {
        let theta = 0.5f64;
        let normals = groove(theta, 64);
        let (mixture, report) = fit(&normals, None, &farthest_lobes(&normals, 4));
        assert!(report.iterations <= MAX_EM_ITERATIONS);
        assert_eq!(mixture.distinct_lobes(0.1, 0.02), 2, "{mixture:?}");
        // The two facets, each half of the mass.
        for want in [
            DVec3::new(theta.sin(), 0.0, theta.cos()),
            DVec3::new(-theta.sin(), 0.0, theta.cos()),
        ] {
            let mass: f64 = mixture
                .lobes
                .iter()
                .filter(|l| l.mu.dot(want) > 0.99)
                .map(|l| l.alpha)
                .sum();
            assert!(
                (mass - 0.5).abs() < 0.02,
                "facet {want}: mass {mass}; {mixture:?}"
            );
        }
        // A flat texel: every lobe ends on +z.
        let flat: Vec<DVec3> = groove(0.0, 64);
        let (mixture, _) = fit(&flat, None, &farthest_lobes(&flat, 4));
        assert_eq!(mixture.distinct_lobes(0.1, 0.02), 1, "{mixture:?}");
        let alpha: f64 = mixture.lobes.iter().map(|l| l.alpha).sum();
        assert!((alpha - 1.0).abs() < 1e-9);
        // Identical normals: one lobe at the cap, no NaN.
        let same = vec![DVec3::Z; 16];
        let (mixture, _) = fit(&same, None, &farthest_lobes(&same, 2));
        assert!(mixture
            .lobes
            .iter()
            .all(|l| l.kappa.is_finite() && l.mu.is_finite()));
        assert_eq!(mixture.distinct_lobes(0.1, 0.02), 1);
    }

    /// The fit maximizes the likelihood: more lobes never fit worse, and one lobe's fit is the
    /// closed form (μ the mean direction, κ from its length).
    #[test]
    fn more_lobes_fit_at_least_as_well_and_one_lobe_is_the_closed_form() {
        let normals = groove(0.4, 80);
        let mut previous = f64::NEG_INFINITY;
        for j in 1..=4 {
            let (_, report) = fit(&normals, None, &farthest_lobes(&normals, j));
            assert!(
                report.log_likelihood >= previous - 1e-9,
                "J = {j}: {} after {previous}",
                report.log_likelihood
            );
            previous = report.log_likelihood;
        }
        let (one, _) = fit(&normals, None, &farthest_lobes(&normals, 1));
        let mean = normals.iter().copied().sum::<DVec3>() / normals.len() as f64;
        assert!((one.lobes[0].mu - mean.normalize()).length() < 1e-12);
        assert!((one.lobes[0].kappa - kappa_from_length(mean.length())).abs() < 1e-9);
    }

    /// Directions drawn from a two-lobe mixture fall into bins as its density says: Pearson's
    /// χ² over bins of cosine and azimuth about +z, against the 0.1 % quantile.
    #[test]
    fn sampled_directions_follow_the_evaluated_mixture() {
        let mixture = VmfMixture {
            lobes: vec![
                VmfLobe::new(0.65, DVec3::new(0.3, 0.1, 1.0), 12.0),
                VmfLobe::new(0.35, DVec3::new(-0.5, 0.2, 0.8), 40.0),
            ],
        };
        let (cos_bins, phi_bins) = (24usize, 24usize);
        let samples = 200_000usize;
        let mut counts = vec![0f64; cos_bins * phi_bins];
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let bin = |d: DVec3| {
            let c = ((d.z + 1.0) / 2.0 * cos_bins as f64).min(cos_bins as f64 - 1.0) as usize;
            let phi = d.y.atan2(d.x) + std::f64::consts::PI;
            let p = (phi / (2.0 * std::f64::consts::PI) * phi_bins as f64)
                .min(phi_bins as f64 - 1.0) as usize;
            c * phi_bins + p
        };
        for _ in 0..samples {
            let u = (next(), next());
            counts[bin(mixture.sample(u))] += 1.0;
        }
        // Expected counts: the density integrated over each bin (z-slab × azimuth wedge: equal
        // solid angle per bin), by a fine midpoint grid.
        let sub = 12usize;
        let mut chi2 = 0.0;
        let mut dof = 0usize;
        for c in 0..cos_bins {
            for p in 0..phi_bins {
                let mut mass = 0.0;
                for a in 0..sub {
                    for b in 0..sub {
                        let z = -1.0
                            + 2.0 * (c as f64 + (a as f64 + 0.5) / sub as f64) / cos_bins as f64;
                        let phi = -std::f64::consts::PI
                            + 2.0
                                * std::f64::consts::PI
                                * (p as f64 + (b as f64 + 0.5) / sub as f64)
                                / phi_bins as f64;
                        let s = (1.0 - z * z).max(0.0).sqrt();
                        mass += mixture.density(DVec3::new(s * phi.cos(), s * phi.sin(), z));
                    }
                }
                let solid_angle = 4.0 * std::f64::consts::PI / (cos_bins * phi_bins) as f64;
                let expected = mass / (sub * sub) as f64 * solid_angle * samples as f64;
                if expected >= 5.0 {
                    chi2 += (counts[c * phi_bins + p] - expected).powi(2) / expected;
                    dof += 1;
                }
            }
        }
        let dof = (dof - 1) as f64;
        // Wilson–Hilferty: the 99.9 % quantile of χ²(dof).
        let z = 3.09;
        let limit = dof * (1.0 - 2.0 / (9.0 * dof) + z * (2.0 / (9.0 * dof)).sqrt()).powi(3);
        assert!(dof > 50.0, "too few bins with mass: {dof}");
        assert!(
            chi2 < limit,
            "χ² {chi2:.1} over {dof} degrees of freedom (limit {limit:.1})"
        );
    }
}
