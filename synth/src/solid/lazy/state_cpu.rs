//! The CPU reference of lazy synthesis: the dependency sets synthesized level by level,
//! stage by stage, with every computed version of every voxel kept for later requests.
//!
//! Memory policy: everything is kept (each voxel's versions 0..=P at its level), so a later
//! request never recomputes a version; [`LazySolidCpu::bytes`] reports the size. Each
//! version is a function of absolute positions only, so the result equals the full-volume
//! synthesizer's on every requested voxel, and a sequence of requests equals one request of
//! their union.

use super::deps::{class_index, dependencies_cpu, Dependencies};
use super::keys::{check_request, lazy_key, lazy_position};
use crate::solid::analysis::SolidAnalysis;
use crate::solid::candidates::SolidCandidates;
use crate::solid::cpu::{check_levels, correct_voxel, offset27, upsample_voxel};
use crate::solid::schedule::level_schedules;
use crate::{SynthParams, SynthResult};
use rayon::prelude::*;
use std::collections::HashMap;

/// Lazy synthesis state on the CPU: per level, each computed voxel's versions.
#[derive(Clone, Debug, Default)]
pub struct LazySolidCpu {
    levels: Vec<HashMap<u64, Vec<[u32; 3]>>>,
    computed: Vec<u64>,
}

impl LazySolidCpu {
    /// An empty state.
    pub fn new() -> LazySolidCpu {
        LazySolidCpu::default()
    }

    /// Versions of voxel `key` of level `level` computed so far.
    pub fn versions(&self, level: usize, key: u64) -> u32 {
        self.levels
            .get(level)
            .and_then(|m| m.get(&key))
            .map_or(0, |v| v.len() as u32)
    }

    /// Voxel versions computed per level over every request so far.
    pub fn computed(&self) -> &[u64] {
        &self.computed
    }

    /// Bytes of the kept state: a key and 12 bytes per version.
    pub fn bytes(&self) -> u64 {
        self.levels
            .iter()
            .flat_map(|m| m.values())
            .map(|v| 8 + 12 * v.len() as u64)
            .sum()
    }

    /// The dependency sets of `requested` given what is already computed.
    pub fn dependencies(&self, requested: &[u64], params: &SynthParams) -> Dependencies {
        dependencies_cpu(requested, &level_schedules(params), &|l, k| {
            self.versions(l, k)
        })
    }

    /// Synthesizes the finest-level voxels at `requested` (absolute positions) and returns
    /// their final triples in the same order. Every request to one state must use the same
    /// analysis, candidates and parameters.
    ///
    /// # Errors
    /// A position outside the key range, or parameters that do not fit the analysis.
    pub fn request(
        &mut self,
        analysis: &SolidAnalysis,
        candidates: &SolidCandidates,
        params: &SynthParams,
        requested: &[[i32; 3]],
    ) -> SynthResult<Vec<[u32; 3]>> {
        check_levels(analysis, candidates, params)?;
        for &p in requested {
            check_request(p)?;
        }
        let levels = analysis.levels.len();
        self.levels.resize_with(levels, HashMap::new);
        self.computed.resize(levels, 0);
        let keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
        let deps = self.dependencies(&keys, params);
        let schedules = level_schedules(params);
        for (l, d) in deps.levels.iter().enumerate() {
            let schedule = schedules[l];
            let l32 = l as u32;
            // Stage 0: upsample the voxels to store with no version yet from their final
            // parents. A voxel needed only upsampled is not stored: its readers upsample it.
            let store_from = schedule.final_stage().min(1);
            let fresh: Vec<(u64, [u32; 3])> = (0..d.len())
                .into_par_iter()
                .filter(|&i| d.need[i] as u32 >= store_from && self.versions(l, d.keys[i]) == 0)
                .map(|i| d.keys[i])
                .map(|k| {
                    let p = lazy_position(k);
                    (k, self.upsampled(analysis, params, l, p))
                })
                .collect();
            self.computed[l] += fresh.len() as u64;
            for (k, t) in fresh {
                self.levels[l].insert(k, vec![t]);
            }
            for stage in 1..=schedule.final_stage() {
                let state = &self.levels[l];
                let updated: Vec<(u64, [u32; 3])> = (0..d.len())
                    .into_par_iter()
                    .filter(|&i| d.need[i] as u32 >= stage)
                    .map(|i| d.keys[i])
                    .filter(|&k| {
                        let class = class_index(lazy_position(k));
                        schedule.corrects(stage, class)
                            && state[&k].len() == schedule.version_at(stage, class) as usize
                    })
                    .map(|k| {
                        let p = lazy_position(k);
                        let around: [[u32; 3]; 27] = std::array::from_fn(|n| {
                            let o = offset27(n);
                            if o.iter().all(|&v| v != 0) {
                                return [0; 3];
                            }
                            let q = [p[0] + o[0], p[1] + o[1], p[2] + o[2]];
                            let v = schedule.version_at(stage - 1, class_index(q)) as usize;
                            match state.get(&lazy_key(q)) {
                                Some(versions) => versions[v],
                                None => {
                                    assert_eq!(v, 0, "only an upsampled read is not stored");
                                    self.upsampled(analysis, params, l, q)
                                }
                            }
                        });
                        (
                            k,
                            correct_voxel(analysis, candidates, l32, params.keep_current, &around),
                        )
                    })
                    .collect();
                self.computed[l] += updated.len() as u64;
                let state = &mut self.levels[l];
                for (k, t) in updated {
                    state
                        .get_mut(&k)
                        .expect("an updated voxel was upsampled")
                        .push(t);
                }
            }
        }
        let finest = levels - 1;
        let last = params.passes[finest] as usize;
        Ok(keys.iter().map(|k| self.levels[finest][k][last]).collect())
    }

    /// Version 0 of voxel `p` of level `l`: upsampled from its parent's final version (the
    /// parent level must hold it), for the voxels stored and for those read only upsampled.
    fn upsampled(
        &self,
        analysis: &SolidAnalysis,
        params: &SynthParams,
        l: usize,
        p: [i32; 3],
    ) -> [u32; 3] {
        let parent = l.checked_sub(1).map(|above| {
            let up = lazy_key(p.map(|v| v.div_euclid(2)));
            self.levels[above][&up][params.passes[above] as usize]
        });
        upsample_voxel(analysis, params, l as u32, p, parent)
    }
}
