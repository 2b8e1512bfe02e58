//! Which region of every pyramid level a window of the unbounded output plane needs.
//!
//! Synthesis is spatially deterministic: every operation depends only on absolute positions,
//! so any window can be synthesized on its own, provided each level is computed over enough
//! padding that the pixels the next level reads are exactly those of the infinite synthesis.
//!
//! Padding formula. A correction subpass updates a pixel from its 3×3 neighbourhood (radius
//! `r = 1`: the neighbourhood compared and the neighbours whose similarity sets give the
//! candidates). A pixel at the border of the computed region cannot be corrected, so after
//! one subpass the pixels that may differ from the infinite synthesis form a ring of depth at
//! most 1, and every later subpass can widen it by `r`. With `P` passes of `S = 4` subpasses,
//!
//! ```text
//!     c_l = P_l · S · r = 4 P_l               (P_l passes at level l)
//!     C_l = V_l grown by c_l on every side     (region computed at level l)
//!     V_(l−1) = [floor(C_l.min / 2), floor((C_l.max − 1) / 2) + 1)   (parents of C_l)
//!     V_L = the requested window
//! ```
//!
//! where `V_l` is the region that must come out exact at level `l`. Upsampling and jitter are
//! per-pixel, so they add no padding. `c` is an upper bound (within a pass the parity classes
//! interleave, so the ring grows more slowly in practice), chosen because it is simple to prove.

/// A rectangle of one level, in absolute pixel positions of that level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// Absolute position of the first pixel.
    pub origin: [i32; 2],
    /// Width and height.
    pub size: [u32; 2],
}

impl Region {
    /// Pixels in the region.
    pub fn pixels(&self) -> usize {
        self.size[0] as usize * self.size[1] as usize
    }

    fn grown(self, by: u32) -> Region {
        Region {
            origin: [self.origin[0] - by as i32, self.origin[1] - by as i32],
            size: [self.size[0] + 2 * by, self.size[1] + 2 * by],
        }
    }

    fn parents(self) -> Region {
        let lo = self.origin.map(|o| o.div_euclid(2));
        let hi = [0, 1].map(|a| (self.origin[a] + self.size[a] as i32 - 1).div_euclid(2) + 1);
        Region {
            origin: lo,
            size: [(hi[0] - lo[0]) as u32, (hi[1] - lo[1]) as u32],
        }
    }
}

/// Subpasses of one correction pass (2×2 parity classes).
pub const SUBPASSES: u32 = 4;

/// Padding `c` each level adds for `passes` correction passes (see the module docs).
pub fn correction_padding(passes: u32) -> u32 {
    passes * SUBPASSES
}

/// The regions to compute at every level for `window` (a region of the finest level), given
/// the correction passes of every level (coarsest first; one entry per level).
pub fn plan_regions(window: Region, passes: &[u32]) -> Vec<Region> {
    let mut regions = Vec::with_capacity(passes.len());
    let mut exact = window;
    for &p in passes.iter().rev() {
        let computed = exact.grown(correction_padding(p));
        regions.push(computed);
        exact = computed.parents();
    }
    regions.reverse();
    regions
}
