//! Dependency sets: which voxels of every level, up to which stage, a set of requested
//! finest-level voxels needs (thesis 003 lines 1083–1096; `shared/notes/003A.md` §5.3.7).
//!
//! A level's stages are 0 (after upsampling and jitter) and `k = 1..=8P` (after subpass `k`,
//! which updates the voxels of parity class `CLASSES_3D[(k − 1) mod 8]`), or `k = 1..=P` for
//! a parallel level, whose every stage updates every voxel (`solid/schedule.rs`). Walking the
//! stages backwards from the voxels that must be final, a voxel needed after a stage that
//! corrects it needs its 18 plane neighbours (the voxels the correction reads: the three
//! planes through it, less itself) after stage `k − 1`; any other voxel needed after `k` is
//! needed after `k − 1` unchanged. The sets are nested (needed after `k` implies after `k − 1`), so
//! one number per voxel says it all: the last stage it is needed at. A voxel needed at stage
//! 0 needs its parent final at the level above.
//!
//! A voxel changes only at its class's subpass of each pass, so its value after stage `k` is
//! its version `⌊(k + 7 − i) / 8⌋` (`i` its class's place in the subpass order; `k` on a
//! parallel level): version 0 upsampled, version `j` after pass `j`. Lazy synthesis keeps every version it computed,
//! and the walk stops at a voxel whose needed version is already known, which is how a later
//! request reuses an earlier one's work.

use super::keys::{lazy_key, lazy_position};
use crate::solid::plan::CLASSES_3D;
use crate::solid::schedule::LevelSchedule;
use std::collections::HashMap;

/// The 18 voxels a correction reads besides the voxel itself: offsets with at least one zero
/// component, the centre excluded (x fastest, then y, then z).
pub const PLANE_NEIGHBOURS: [[i32; 3]; 18] = {
    let mut out = [[0i32; 3]; 18];
    let mut n = 0;
    let mut i: i32 = 0;
    while i < 27 {
        let d = [i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1];
        let zeros = (d[0] == 0) as u32 + (d[1] == 0) as u32 + (d[2] == 0) as u32;
        if zeros == 1 || zeros == 2 {
            out[n] = d;
            n += 1;
        }
        i += 1;
    }
    assert!(n == 18);
    out
};

/// The place of position `p`'s parity class in the subpass order [`CLASSES_3D`].
pub fn class_index(p: [i32; 3]) -> u32 {
    let parity = p.map(|v| v & 1);
    CLASSES_3D
        .iter()
        .position(|&c| c == parity)
        .expect("every parity is a class") as u32
}

/// The voxels one level needs: sorted unique keys and, for each, the last stage it is needed
/// at.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LevelDeps {
    /// Keys ([`lazy_key`]) in increasing order.
    pub keys: Vec<u64>,
    /// The last stage each key is needed at.
    pub need: Vec<u8>,
}

impl LevelDeps {
    /// Voxels in the set.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// How many versions (0 up to the one at its last stage) voxel `i` needs on a level
    /// corrected by `schedule`.
    pub fn versions_needed(&self, i: usize, schedule: &LevelSchedule) -> u32 {
        schedule.version_at(
            self.need[i] as u32,
            class_index(lazy_position(self.keys[i])),
        ) + 1
    }
}

/// The voxels every level needs, coarsest level first.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Dependencies {
    /// One set per level.
    pub levels: Vec<LevelDeps>,
}

impl Dependencies {
    /// Voxel versions the sets ask for beyond the `known` ones (the work of a request).
    pub fn new_versions(
        &self,
        schedules: &[LevelSchedule],
        known: &dyn Fn(usize, u64) -> u32,
    ) -> u64 {
        self.levels
            .iter()
            .enumerate()
            .map(|(l, d)| {
                (0..d.len())
                    .map(|i| {
                        d.versions_needed(i, &schedules[l])
                            .saturating_sub(known(l, d.keys[i])) as u64
                    })
                    .sum::<u64>()
            })
            .sum()
    }
}

/// The dependency sets of the finest-level voxels `requested` (keys, any order, repeats
/// allowed) for a pyramid corrected by `schedules[l]` at level `l`; `known(l, key)` says how
/// many versions of a voxel are already computed (0 for none), and the walk stops where the
/// needed version is known. The CPU reference of the GPU dependency walk.
pub fn dependencies_cpu(
    requested: &[u64],
    schedules: &[LevelSchedule],
    known: &dyn Fn(usize, u64) -> u32,
) -> Dependencies {
    let mut levels = vec![LevelDeps::default(); schedules.len()];
    let mut target: Vec<u64> = requested.to_vec();
    target.sort_unstable();
    target.dedup();
    for l in (0..schedules.len()).rev() {
        let need = walk_level(&target, schedules[l], &|k| known(l, k), &mut |_, _| {});
        let mut set: Vec<(u64, u32)> = need.into_iter().collect();
        set.sort_unstable();
        target = set
            .iter()
            .filter(|&&(k, _)| known(l, k) == 0)
            .map(|&(k, _)| lazy_key(lazy_position(k).map(|v| v.div_euclid(2))))
            .collect();
        target.dedup();
        levels[l] = LevelDeps {
            keys: set.iter().map(|s| s.0).collect(),
            need: set.iter().map(|s| s.1 as u8).collect(),
        };
    }
    levels.into()
}

/// One level's backward walk from `target` (needed final): each voxel's last needed stage.
/// `on_stage(stage, added)` hears how many voxels each stage's expansion added to the set.
fn walk_level(
    target: &[u64],
    s: LevelSchedule,
    known: &dyn Fn(u64) -> u32,
    on_stage: &mut dyn FnMut(u32, usize),
) -> HashMap<u64, u32> {
    let last = s.final_stage();
    let mut need: HashMap<u64, u32> = target.iter().map(|&k| (k, last)).collect();
    for stage in (1..=last).rev() {
        let expand: Vec<[i32; 3]> = need
            .iter()
            .filter(|&(_, &n)| n >= stage)
            .map(|(&k, _)| (k, lazy_position(k)))
            .filter(|&(k, p)| {
                let class = class_index(p);
                s.corrects(stage, class) && known(k) <= s.version_at(stage, class)
            })
            .map(|(_, p)| p)
            .collect();
        let before = need.len();
        for p in expand {
            for d in PLANE_NEIGHBOURS {
                let e = need
                    .entry(lazy_key([p[0] + d[0], p[1] + d[1], p[2] + d[2]]))
                    .or_insert(stage - 1);
                *e = (*e).max(stage - 1);
            }
        }
        on_stage(stage, need.len() - before);
    }
    need
}

/// Where a fresh state's finest level gets its voxels from: for the finest-level voxels
/// `requested` and the finest level's `schedule`, the voxels each stage of the backward walk
/// adds (last stage first), and how many of the set are needed only upsampled (stage 0, read
/// in place and not stored). What `bench lazy` prints to locate the dependency chain.
pub fn finest_growth_cpu(requested: &[u64], schedule: LevelSchedule) -> (Vec<(u32, usize)>, usize) {
    let mut target = requested.to_vec();
    target.sort_unstable();
    target.dedup();
    let mut growth = Vec::new();
    let need = walk_level(&target, schedule, &|_| 0, &mut |stage, added| {
        growth.push((stage, added))
    });
    let upsampled_only = need.values().filter(|&&n| n == 0).count();
    (growth, upsampled_only)
}

impl From<Vec<LevelDeps>> for Dependencies {
    fn from(levels: Vec<LevelDeps>) -> Dependencies {
        Dependencies { levels }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::schedule::ordered_schedules;

    #[test]
    fn class_places_follow_the_subpass_order() {
        for (i, c) in CLASSES_3D.iter().enumerate() {
            assert_eq!(class_index(*c), i as u32);
            assert_eq!(class_index([c[0] - 2, c[1] + 4, c[2] - 6]), i as u32);
        }
    }

    #[test]
    fn every_updated_voxel_has_its_neighbours_one_stage_earlier() {
        let requested: Vec<u64> = [[0, 0, 0], [5, -3, 2], [6, -3, 2], [-9, 9, 1]]
            .map(lazy_key)
            .to_vec();
        let mut schedules = ordered_schedules(&[2, 1, 2, 1]);
        schedules[3].parallel = true;
        let deps = dependencies_cpu(&requested, &schedules, &|_, _| 0);
        for (l, d) in deps.levels.iter().enumerate() {
            let need: HashMap<u64, u32> = d
                .keys
                .iter()
                .zip(&d.need)
                .map(|(&k, &n)| (k, n as u32))
                .collect();
            assert!(d.keys.windows(2).all(|w| w[0] < w[1]));
            for (&k, &n) in &need {
                let p = lazy_position(k);
                for stage in 1..=n {
                    if schedules[l].corrects(stage, class_index(p)) {
                        for dd in PLANE_NEIGHBOURS {
                            let q = lazy_key([p[0] + dd[0], p[1] + dd[1], p[2] + dd[2]]);
                            assert!(need.get(&q).is_some_and(|&m| m >= stage - 1));
                        }
                    }
                }
                if l > 0 {
                    let parent = lazy_key(p.map(|v| v.div_euclid(2)));
                    let above = &deps.levels[l - 1];
                    let i = above.keys.binary_search(&parent).expect("parent present");
                    assert_eq!(above.need[i] as u32, schedules[l - 1].final_stage());
                }
            }
        }
        for k in requested {
            let fin = deps.levels.last().unwrap();
            let i = fin.keys.binary_search(&k).unwrap();
            assert_eq!(fin.need[i] as u32, 1);
            // A parallel finest pass corrects only the requested voxels.
            let corrected = fin.need.iter().filter(|&&n| n == 1).count();
            assert_eq!(corrected, 4);
        }
    }

    #[test]
    fn known_versions_stop_the_walk() {
        let requested = vec![lazy_key([1, 2, 3])];
        let schedules = ordered_schedules(&[1, 1]);
        let all = dependencies_cpu(&requested, &schedules, &|_, _| 0);
        let known = |l: usize, k: u64| {
            let d = &all.levels[l];
            d.keys
                .binary_search(&k)
                .map_or(0, |i| d.versions_needed(i, &schedules[l]))
        };
        let again = dependencies_cpu(&requested, &schedules, &known);
        assert_eq!(again.new_versions(&schedules, &known), 0);
        assert_eq!(
            again.levels[0].len(),
            0,
            "nothing above a known voxel is needed"
        );
        assert!(all.new_versions(&schedules, &|_, _| 0) > 0);
    }
}
