//! Which box of every pyramid level a box of the unbounded volume needs: the 2D plan
//! (`synth/plan.rs`) in 3D. A correction subpass reads the 3×3×3 neighbourhood (radius 1), so
//! with `P_l` passes of 8 parity subpasses the ring that may differ from the infinite
//! synthesis grows by at most `c_l = 8 P_l` voxels per side:
//!
//! ```text
//!     C_l     = V_l grown by 8 P_l on every side       (box computed at level l)
//!     V_(l−1) = [floor(C_l.min / 2), floor((C_l.max − 1) / 2) + 1)   (parents of C_l)
//!     V_L     = the requested box
//! ```

/// Parity subpasses of one 3D correction pass (2×2×2 classes).
pub const SUBPASSES_3D: u32 = 8;

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

    fn grown(self, by: u32) -> VolumeBox {
        VolumeBox {
            origin: self.origin.map(|o| o - by as i32),
            size: self.size.map(|s| s + 2 * by),
        }
    }

    fn parents(self) -> VolumeBox {
        let lo = self.origin.map(|o| o.div_euclid(2));
        let hi: [i32; 3] =
            std::array::from_fn(|a| (self.origin[a] + self.size[a] as i32 - 1).div_euclid(2) + 1);
        VolumeBox {
            origin: lo,
            size: std::array::from_fn(|a| (hi[a] - lo[a]) as u32),
        }
    }
}

/// The boxes to compute at every level (coarsest first) for `window` of the finest level,
/// given each level's correction passes.
pub fn plan_boxes(window: VolumeBox, passes: &[u32]) -> Vec<VolumeBox> {
    let mut boxes = Vec::with_capacity(passes.len());
    let mut exact = window;
    for &p in passes.iter().rev() {
        let computed = exact.grown(p * SUBPASSES_3D);
        boxes.push(computed);
        exact = computed.parents();
    }
    boxes.reverse();
    boxes
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn boxes_follow_the_formula() {
        let w = VolumeBox {
            origin: [-5, 3, 0],
            size: [20, 10, 4],
        };
        let boxes = plan_boxes(w, &[1, 2]);
        assert_eq!(boxes[1].origin, [-21, -13, -16]);
        assert_eq!(boxes[1].size, [52, 42, 36]);
        // Parents of x in -21..31 are -11..16, grown by 8.
        assert_eq!(boxes[0].origin[0], -19);
        assert_eq!(boxes[0].size[0], 43);
        let b = boxes[0];
        assert_eq!(b.index(b.position(1234)), 1234);
    }
}
