//! The MIP pyramid of a normal map as von Mises–Fisher mixtures (seed 000 Algorithm 7.1 per
//! texel of every level), beside the plain MIP of averaged normals it replaces.
//!
//! **Why.** A texel of level `k` covers `2^k × 2^k` normals of the map. Averaging them (the
//! plain MIP) keeps one direction and loses the spread: a V-groove's two facets become a flat
//! normal and the far field turns shiny. The mixture keeps `J` lobes per texel, fitted by EM to
//! *all* the fine normals the texel covers, started from the `J` farthest apart of its four
//! children's lobes (Hochbaum–Shmoys, T:3436–3448).
//!
//! Maps are the glint material's [`NormalExample`]s (square, power-of-two edge, tangent
//! space), read by the same loader.

use super::mixture::{farthest_lobes, fit};
use super::vmf::{VmfLobe, MAX_KAPPA};
use crate::glint::NormalExample;
use glam::DVec3;
use rayon::prelude::*;

/// Fewest and most lobes per texel: the thesis finds 3–4 "excellent", 6 more so.
pub const LOBES_PER_TEXEL: std::ops::RangeInclusive<usize> =
    1..=crate::shader_constants::VMF_MAX_LOBES as usize;

/// One level: `size`² texels of `lobes_per_texel` lobes each, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct VmfLevel {
    /// Edge in texels.
    pub size: usize,
    /// `size² · J` lobes; a texel's unused lobes have weight 0.
    pub lobes: Vec<VmfLobe>,
}

/// Every level of a map, finest (the map itself, one sharp lobe per texel) first.
#[derive(Clone, Debug, PartialEq)]
pub struct VmfPyramid {
    /// Lobes per texel (`J`).
    pub lobes_per_texel: usize,
    /// Levels 0 (finest) to log2(edge) (one texel).
    pub levels: Vec<VmfLevel>,
}

/// The unit normal of a tangent-space texel (n_z implied by n_x, n_y).
pub fn texel_normal(n: glam::Vec2) -> DVec3 {
    let (x, y) = (f64::from(n.x), f64::from(n.y));
    DVec3::new(x, y, (1.0 - x * x - y * y).max(0.0).sqrt()).normalize()
}

impl VmfPyramid {
    /// Fits every level of `map` with `lobes_per_texel` lobes per texel.
    ///
    /// # Errors
    /// A lobe count outside [`LOBES_PER_TEXEL`], named with its limit.
    pub fn build(map: &NormalExample, lobes_per_texel: usize) -> Result<VmfPyramid, String> {
        if !LOBES_PER_TEXEL.contains(&lobes_per_texel) {
            return Err(format!(
                "lobes per texel is {lobes_per_texel}; it must lie in {}..={}",
                LOBES_PER_TEXEL.start(),
                LOBES_PER_TEXEL.end()
            ));
        }
        let j = lobes_per_texel;
        let size = map.size();
        let normals = map_normals(map);
        let mut levels = vec![finest_level(&normals, size, j)];
        while levels.last().expect("one level").size > 1 {
            let child = levels.last().expect("one level");
            let edge = child.size / 2;
            let span = size / edge;
            let lobes: Vec<VmfLobe> = (0..edge * edge)
                .into_par_iter()
                .flat_map_iter(|t| {
                    let (tx, ty) = (t % edge, t / edge);
                    let covered: Vec<DVec3> = (0..span * span)
                        .map(|i| normals[(ty * span + i / span) * size + tx * span + i % span])
                        .collect();
                    let (mixture, _) = fit(&covered, None, &level_start(child, j, tx, ty));
                    mixture.lobes
                })
                .collect();
            levels.push(VmfLevel { size: edge, lobes });
        }
        Ok(VmfPyramid {
            lobes_per_texel: j,
            levels,
        })
    }

    /// The lobes of texel (x, y) of level `level`.
    pub fn texel(&self, level: usize, x: usize, y: usize) -> &[VmfLobe] {
        let l = &self.levels[level];
        let j = self.lobes_per_texel;
        let t = y * l.size + x;
        &l.lobes[t * j..(t + 1) * j]
    }
}

/// The unit normals of a map's texels, row by row.
pub fn map_normals(map: &NormalExample) -> Vec<DVec3> {
    map.texels().iter().map(|&n| texel_normal(n)).collect()
}

/// Level 0: one sharp lobe of weight 1 per texel about its normal (the other `j − 1` lobes
/// weightless).
pub fn finest_level(normals: &[DVec3], size: usize, j: usize) -> VmfLevel {
    VmfLevel {
        size,
        lobes: normals
            .iter()
            .flat_map(|&n| {
                (0..j).map(move |i| VmfLobe::new(if i == 0 { 1.0 } else { 0.0 }, n, MAX_KAPPA))
            })
            .collect(),
    }
}

/// Where EM starts for texel (tx, ty) of the level above `child`: the `j` farthest apart of its
/// four children's weighted lobe directions (Hochbaum–Shmoys, T:3436–3448).
pub fn level_start(child: &VmfLevel, j: usize, tx: usize, ty: usize) -> Vec<VmfLobe> {
    let starts: Vec<DVec3> = [(0, 0), (1, 0), (0, 1), (1, 1)]
        .iter()
        .flat_map(|&(dx, dy)| {
            let c = (2 * ty + dy) * child.size + 2 * tx + dx;
            child.lobes[c * j..(c + 1) * j]
                .iter()
                .filter(|l| l.alpha > 0.0)
                .map(|l| l.mu)
        })
        .collect();
    farthest_lobes(&starts, j)
}

/// The plain MIP of averaged normals (renormalized), finest first: the baseline the mixture
/// is measured against.
pub fn mean_normal_levels(map: &NormalExample) -> Vec<Vec<DVec3>> {
    let size = map.size();
    let mut levels = vec![map
        .texels()
        .iter()
        .map(|&n| texel_normal(n))
        .collect::<Vec<_>>()];
    let mut sums: Vec<DVec3> = levels[0].clone();
    let mut edge = size;
    while edge > 1 {
        let half = edge / 2;
        sums = (0..half * half)
            .map(|t| {
                let (x, y) = (t % half, t / half);
                sums[2 * y * edge + 2 * x]
                    + sums[2 * y * edge + 2 * x + 1]
                    + sums[(2 * y + 1) * edge + 2 * x]
                    + sums[(2 * y + 1) * edge + 2 * x + 1]
            })
            .collect();
        edge = half;
        levels.push(sums.iter().map(|s| s.normalize_or(DVec3::Z)).collect());
    }
    levels
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A V-groove map: columns alternate between facets tilted by ±θ about y.
    fn grooves(size: usize, theta: f32) -> NormalExample {
        let texels = (0..size * size)
            .map(|i| {
                let side = if i % 2 == 0 { 1.0 } else { -1.0 };
                Vec2::new(side * theta.sin(), 0.0)
            })
            .collect();
        NormalExample::from_normals("grooves", size, texels).unwrap()
    }

    #[test]
    fn a_v_groove_keeps_two_lobes_at_every_level_where_the_plain_mip_goes_flat() {
        let theta = 0.6f32;
        let map = grooves(16, theta);
        let pyramid = VmfPyramid::build(&map, 4).unwrap();
        let plain = mean_normal_levels(&map);
        assert_eq!(pyramid.levels.len(), 5);
        let facet = f64::from(theta.sin());
        for (level, flat) in plain.iter().enumerate().skip(1) {
            let lobes = pyramid.texel(level, 0, 0);
            let mixture = super::super::mixture::VmfMixture {
                lobes: lobes.to_vec(),
            };
            assert_eq!(
                mixture.distinct_lobes(0.1, 0.02),
                2,
                "level {level}: {lobes:?}"
            );
            for side in [1.0, -1.0] {
                let mass: f64 = lobes
                    .iter()
                    .filter(|l| (l.mu.x - side * facet).abs() < 1e-3)
                    .map(|l| l.alpha)
                    .sum();
                assert!((mass - 0.5).abs() < 1e-6, "level {level}: {lobes:?}");
            }
            // The plain MIP averages the facets to the flat normal.
            assert!((flat[0] - DVec3::Z).length() < 1e-6);
        }
    }

    #[test]
    fn a_flat_map_has_one_lobe_everywhere_and_bad_lobe_counts_are_refused() {
        let map = NormalExample::from_normals("flat", 8, vec![Vec2::ZERO; 64]).unwrap();
        let pyramid = VmfPyramid::build(&map, 3).unwrap();
        for (k, level) in pyramid.levels.iter().enumerate() {
            for t in 0..level.size * level.size {
                let lobes = pyramid.texel(k, t % level.size, t / level.size);
                let mixture = super::super::mixture::VmfMixture {
                    lobes: lobes.to_vec(),
                };
                assert_eq!(mixture.distinct_lobes(0.05, 1e-9), 1, "level {k}");
                let alpha: f64 = lobes.iter().map(|l| l.alpha).sum();
                assert!((alpha - 1.0).abs() < 1e-9);
            }
        }
        for bad in [0, 9] {
            let err = VmfPyramid::build(&map, bad).unwrap_err();
            assert!(
                err.contains("lobes per texel") && err.contains("1..=8"),
                "{err}"
            );
        }
    }
}
