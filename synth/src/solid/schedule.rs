//! How one level's correction passes run, defined once for the dense synthesizer, its plan and
//! lazy synthesis (`docs/lazy.md`, "Dependency chains").
//!
//! **Ordered** (the thesis' scheme): a pass is eight subpasses, one per 2×2×2 parity class in
//! the Gray-code order of [`CLASSES_3D`](super::CLASSES_3D); a voxel reads the neighbours its
//! pass already corrected. Stage `k = 1..=8P` is the state after subpass `k`.
//!
//! **Parallel** (Jacobi): a pass corrects every voxel at once from the state after the previous
//! pass. Stage `k = 1..=P` is the state after pass `k`. A voxel's correction then depends on
//! its 18 plane neighbours one pass earlier only, instead of on a chain through the classes
//! corrected before it (up to 5, 3 and 2 voxels a side along x, y and z per ordered pass): with
//! one parallel pass at the finest level, lazy synthesis corrects exactly the requested voxels
//! and reads their neighbours' upsampled triples. Measured in `docs/lazy.md`.
//!
//! A voxel's **version** after stage `k` counts the subpasses up to `k` that corrected it:
//! version 0 upsampled, version `j` after pass `j`, in both kinds.

use super::plan::SUBPASSES_3D;
use crate::SynthParams;

/// Marks a stage that corrects every class (a parallel pass) where a class place is expected
/// (the kernels' `cls` push constant).
pub const ALL_CLASSES: u32 = SUBPASSES_3D;

/// One level's correction passes and how they run (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LevelSchedule {
    /// Correction passes.
    pub passes: u32,
    /// Every voxel corrected at once per pass (Jacobi) instead of in eight ordered subpasses.
    pub parallel: bool,
}

impl LevelSchedule {
    /// The last stage: after the last subpass (ordered) or pass (parallel).
    pub fn final_stage(&self) -> u32 {
        if self.parallel {
            self.passes
        } else {
            self.passes * SUBPASSES_3D
        }
    }

    /// The class place stage `stage` (1-based) corrects, or [`ALL_CLASSES`].
    pub fn stage_class(&self, stage: u32) -> u32 {
        if self.parallel {
            ALL_CLASSES
        } else {
            (stage - 1) % SUBPASSES_3D
        }
    }

    /// Whether stage `stage` corrects the voxels of class place `class`.
    pub fn corrects(&self, stage: u32, class: u32) -> bool {
        self.parallel || (stage - 1) % SUBPASSES_3D == class
    }

    /// The version a voxel of class place `class` holds after stage `stage`.
    pub fn version_at(&self, stage: u32, class: u32) -> u32 {
        if self.parallel {
            stage
        } else {
            (stage + SUBPASSES_3D - 1 - class) / SUBPASSES_3D
        }
    }
}

/// Every level's schedule, coarsest first: `params.passes`, the last
/// `params.parallel_levels` levels parallel.
pub fn level_schedules(params: &SynthParams) -> Vec<LevelSchedule> {
    let levels = params.passes.len();
    let first_parallel = levels.saturating_sub(params.parallel_levels as usize);
    params
        .passes
        .iter()
        .enumerate()
        .map(|(l, &passes)| LevelSchedule {
            passes,
            parallel: l >= first_parallel,
        })
        .collect()
}

/// Ordered schedules with `passes[l]` passes (what a pass list alone describes).
pub fn ordered_schedules(passes: &[u32]) -> Vec<LevelSchedule> {
    passes
        .iter()
        .map(|&passes| LevelSchedule {
            passes,
            parallel: false,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordered_versions_follow_the_subpass_order() {
        let s = LevelSchedule {
            passes: 2,
            parallel: false,
        };
        assert_eq!(s.final_stage(), 16);
        for class in 0..8 {
            assert_eq!(s.version_at(0, class), 0);
            assert_eq!(s.version_at(class, class), 0, "before its subpass");
            assert_eq!(s.version_at(class + 1, class), 1, "after its subpass");
            assert_eq!(s.version_at(8, class), 1);
            assert_eq!(s.version_at(8 + class + 1, class), 2);
            assert_eq!(s.version_at(16, class), 2);
            assert!(s.corrects(class + 1, class) && s.corrects(class + 9, class));
            assert!(!s.corrects((class + 1) % 8 + 1, class));
            assert_eq!(s.stage_class(class + 9), class);
        }
    }

    #[test]
    fn parallel_passes_correct_every_class_once_per_stage() {
        let s = LevelSchedule {
            passes: 3,
            parallel: true,
        };
        assert_eq!(s.final_stage(), 3);
        for class in 0..8 {
            for stage in 0..=3 {
                assert_eq!(s.version_at(stage, class), stage);
                if stage > 0 {
                    assert!(s.corrects(stage, class));
                    assert_eq!(s.stage_class(stage), ALL_CLASSES);
                }
            }
        }
    }

    #[test]
    fn the_finest_levels_are_the_parallel_ones() {
        let params = SynthParams::new(5, 1, &[2, 2, 2, 2, 1], &[0.0])
            .unwrap()
            .with_parallel_levels(2)
            .unwrap();
        let s = level_schedules(&params);
        assert_eq!(
            s.iter().map(|s| s.parallel).collect::<Vec<_>>(),
            [false, false, false, true, true]
        );
        assert_eq!(s[4].passes, 1);
    }
}
