//! Which voxels of every pyramid level a box of the unbounded volume needs: the 2D plan
//! (`synth/plan.rs`) in 3D, tightened by the parity of the subpasses.
//!
//! A correction subpass updates the voxels of one 2×2×2 parity class (of their absolute
//! position) and reads their 3×3×3 neighbourhood. Walking the subpasses backwards from the
//! box `R` that must be exact after a subpass of class `c`, the box that must be exact before
//! it is `R` plus the neighbours of `R`'s class-`c` voxels: along each axis a side grows by one
//! voxel only when its outermost layer has the parity of `c` on that axis, and then the new
//! outermost layer has the other parity. So a side grows once per change of the class's
//! parity on that axis along the subpass order, and [`CLASSES_3D`] runs through the classes in
//! Gray-code order (one bit changes per step: x four times, y twice, z once per pass), which
//! grows a box by at most 5, 3 and 2 voxels per side and pass along x, y and z instead of the
//! 8 of a radius-1 bound per subpass — at the coarse levels, where the padding is most of the
//! box, about 12× fewer voxels with 2 passes.
//!
//! ```text
//!     R_end(L)  = the requested box
//!     R_before  = grow(R_after, c)    per subpass of class c, last first (skipped if R_after
//!                                     holds no class-c voxel)
//!     C_l       = R_before of the level's first subpass      (box computed at level l)
//!     R_end(l−1)= parents of C_l
//! ```
//!
//! Each subpass updates only the class voxels of its `R_after` (all of whose neighbours lie in
//! `C_l`), so a box synthesized alone equals the same box inside a larger one, bit for bit.
//!
//! A parallel pass (`schedule.rs`) updates every voxel of `R_after` from the state before it,
//! so it grows the box by one voxel on every side.

use super::schedule::LevelSchedule;

/// Parity subpasses of one 3D correction pass (2×2×2 classes).
pub const SUBPASSES_3D: u32 = 8;

/// Parity classes `[x, y, z]` in subpass order: the 3-bit reflected Gray code with x the
/// fastest bit, so that consecutive classes differ along one axis (module docs).
pub const CLASSES_3D: [[i32; 3]; 8] = [
    [0, 0, 0],
    [1, 0, 0],
    [1, 1, 0],
    [0, 1, 0],
    [0, 1, 1],
    [1, 1, 1],
    [1, 0, 1],
    [0, 0, 1],
];

/// An axis-aligned box of one level, in absolute voxel positions of that level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct VolumeBox {
    /// Absolute position of the first voxel.
    pub origin: [i32; 3],
    /// Extent along x, y and z.
    pub size: [u32; 3],
}

impl VolumeBox {
    /// Voxels in the box.
    pub fn voxels(&self) -> usize {
        self.size.iter().map(|&s| s as usize).product()
    }

    /// Row-major index (x fastest, then y, then z) of absolute position `p`, which must lie
    /// inside.
    pub fn index(&self, p: [i32; 3]) -> usize {
        let l = [0, 1, 2].map(|a| (p[a] - self.origin[a]) as usize);
        (l[2] * self.size[1] as usize + l[1]) * self.size[0] as usize + l[0]
    }

    /// The absolute position of row-major index `i`.
    pub fn position(&self, i: usize) -> [i32; 3] {
        let (sx, sy) = (self.size[0] as usize, self.size[1] as usize);
        let l = [i % sx, (i / sx) % sy, i / (sx * sy)];
        std::array::from_fn(|a| self.origin[a] + l[a] as i32)
    }

    /// Whether absolute position `p` lies inside.
    pub fn contains(&self, p: [i32; 3]) -> bool {
        (0..3).all(|a| p[a] >= self.origin[a] && p[a] < self.origin[a] + self.size[a] as i32)
    }

    /// The last position along axis `a`.
    fn last(&self, a: usize) -> i32 {
        self.origin[a] + self.size[a] as i32 - 1
    }

    /// Per axis, the first position of parity `class` inside and how many there are (step 2).
    pub fn class_span(&self, class: [i32; 3]) -> [(i32, u32); 3] {
        std::array::from_fn(|a| {
            let first = self.origin[a] + (class[a] - self.origin[a]).rem_euclid(2);
            let count = if first > self.last(a) {
                0
            } else {
                ((self.last(a) - first) / 2 + 1) as u32
            };
            (first, count)
        })
    }

    /// Voxels of parity `class` inside.
    pub fn class_voxels(&self, class: [i32; 3]) -> u64 {
        self.class_span(class).iter().map(|s| s.1 as u64).product()
    }

    /// This box plus the 3×3×3 neighbours of its voxels of parity `class` (module docs).
    fn grown_for(self, class: [i32; 3]) -> VolumeBox {
        let lo: [i32; 3] =
            std::array::from_fn(|a| self.origin[a] - (self.origin[a] & 1 == class[a]) as i32);
        let hi: [i32; 3] =
            std::array::from_fn(|a| self.last(a) + (self.last(a) & 1 == class[a]) as i32);
        VolumeBox {
            origin: lo,
            size: std::array::from_fn(|a| (hi[a] - lo[a] + 1) as u32),
        }
    }

    /// This box plus one voxel on every side (what a parallel pass reads).
    fn grown_by_one(self) -> VolumeBox {
        VolumeBox {
            origin: self.origin.map(|o| o - 1),
            size: self.size.map(|s| s + 2),
        }
    }

    fn parents(self) -> VolumeBox {
        let lo = self.origin.map(|o| o.div_euclid(2));
        let hi: [i32; 3] = std::array::from_fn(|a| self.last(a).div_euclid(2) + 1);
        VolumeBox {
            origin: lo,
            size: std::array::from_fn(|a| (hi[a] - lo[a]) as u32),
        }
    }
}

/// One correction subpass: the class it updates and the box whose voxels of that class it
/// updates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Subpass {
    /// Parity `[x, y, z]` of the updated voxels' absolute positions; `None` for a parallel
    /// pass, which updates every voxel of the box from the state before it.
    pub class: Option<[i32; 3]>,
    /// The box that must be exact after the subpass (its class voxels are updated).
    pub update: VolumeBox,
}

impl Subpass {
    /// Voxels the subpass updates.
    pub fn updates(&self) -> u64 {
        match self.class {
            Some(class) => self.update.class_voxels(class),
            None => self.update.voxels() as u64,
        }
    }

    /// Per axis, the first updated position, how many there are and their step.
    pub fn span(&self) -> [(i32, u32, u32); 3] {
        match self.class {
            Some(class) => self.update.class_span(class).map(|(f, n)| (f, n, 2)),
            None => std::array::from_fn(|a| (self.update.origin[a], self.update.size[a], 1)),
        }
    }
}

/// What one level computes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LevelPlan {
    /// The box upsampled and jittered (every voxel any subpass reads).
    pub region: VolumeBox,
    /// The subpasses in order (those with no voxel to update are left out).
    pub subpasses: Vec<Subpass>,
}

impl LevelPlan {
    /// Voxel updates of all the level's subpasses.
    pub fn updates(&self) -> u64 {
        self.subpasses.iter().map(Subpass::updates).sum()
    }
}

/// What every level (coarsest first) computes for `window` of the finest level, given each
/// level's correction schedule.
pub fn plan_levels(window: VolumeBox, schedules: &[LevelSchedule]) -> Vec<LevelPlan> {
    let mut plans = Vec::with_capacity(schedules.len());
    let mut need = window;
    for s in schedules.iter().rev() {
        let mut subpasses = Vec::new();
        for _ in 0..s.passes {
            if s.parallel {
                subpasses.push(Subpass {
                    class: None,
                    update: need,
                });
                need = need.grown_by_one();
                continue;
            }
            for &class in CLASSES_3D.iter().rev() {
                if need.class_voxels(class) > 0 {
                    subpasses.push(Subpass {
                        class: Some(class),
                        update: need,
                    });
                    need = need.grown_for(class);
                }
            }
        }
        subpasses.reverse();
        plans.push(LevelPlan {
            region: need,
            subpasses,
        });
        need = need.parents();
    }
    plans.reverse();
    plans
}

/// The boxes every level computes (coarsest first): [`plan_levels`]' regions.
pub fn plan_boxes(window: VolumeBox, schedules: &[LevelSchedule]) -> Vec<VolumeBox> {
    plan_levels(window, schedules)
        .into_iter()
        .map(|p| p.region)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::schedule::ordered_schedules;

    #[test]
    fn consecutive_classes_differ_along_one_axis() {
        for w in CLASSES_3D.windows(2) {
            let changed = (0..3).filter(|&a| w[0][a] != w[1][a]).count();
            assert_eq!(changed, 1, "{w:?}");
        }
        let mut all = CLASSES_3D.to_vec();
        all.sort();
        all.dedup();
        assert_eq!(all.len(), 8);
    }

    #[test]
    fn class_spans_count_the_class_voxels() {
        let b = VolumeBox {
            origin: [-3, 4, 0],
            size: [5, 1, 2],
        };
        for class in CLASSES_3D {
            let brute = (0..b.voxels())
                .filter(|&i| {
                    let p = b.position(i);
                    (0..3).all(|a| p[a].rem_euclid(2) == class[a])
                })
                .count() as u64;
            assert_eq!(b.class_voxels(class), brute, "{class:?}");
        }
    }

    /// Every voxel a subpass updates has its 3×3×3 neighbourhood inside the level's box, and
    /// every voxel needed after a subpass was either updated by it or needed before it.
    #[test]
    fn subpasses_read_inside_the_region_and_cover_what_is_needed() {
        let w = VolumeBox {
            origin: [-5, 3, 0],
            size: [20, 10, 4],
        };
        let mut schedules = ordered_schedules(&[1, 2, 2, 1]);
        schedules[3].parallel = true;
        let plans = plan_levels(w, &schedules);
        for plan in &plans {
            let mut need_after: Option<VolumeBox> = None;
            for s in plan.subpasses.iter().rev() {
                if let Some(after) = need_after {
                    // The box exact after this subpass contains the next one's.
                    assert!((0..3).all(|a| after.origin[a] >= s.update.origin[a]
                        && after.last(a) <= s.update.last(a)));
                }
                for (a, &(first, count, step)) in s.span().iter().enumerate() {
                    if count > 0 {
                        let last = first + step as i32 * (count as i32 - 1);
                        // The neighbours first - 1 and last + 1 lie inside.
                        assert!(first > plan.region.origin[a]);
                        assert!(last < plan.region.last(a));
                    }
                }
                need_after = Some(s.update);
            }
        }
        let finest = plans.last().unwrap();
        assert_eq!(finest.subpasses.last().unwrap().update, w);
        let b = plans[0].region;
        assert_eq!(b.index(b.position(1234 % b.voxels())), 1234 % b.voxels());
    }

    #[test]
    fn padding_per_pass_is_at_most_five_three_two() {
        let w = VolumeBox {
            origin: [0, 0, 0],
            size: [64, 64, 64],
        };
        for origin in [[0, 0, 0], [1, 1, 1], [-7, 2, 5]] {
            let w = VolumeBox { origin, ..w };
            let plan = &plan_levels(w, &ordered_schedules(&[3]))[0];
            for (a, most) in [(0, 5), (1, 3), (2, 2)] {
                let low = w.origin[a] - plan.region.origin[a];
                let high = plan.region.last(a) - w.last(a);
                assert!(
                    low <= 3 * most && high <= 3 * most,
                    "axis {a}: {low} {high}"
                );
            }
        }
    }
}
