//! The period penalty of the correction: a candidate that would make the coherent patch around
//! a pixel span a whole exemplar period ranks behind the others.
//!
//! A coherent patch is a verbatim copy of the exemplar; one that is at least a period wide
//! shows the same exemplar pixel twice, one period apart — the tiling that the period
//! repetition measures (`repetition.rs`) and that the eye sees as a lattice. The
//! neighbourhood energy rewards such copies (they match the exemplar perfectly), so the
//! correction drifts towards them, mostly at the coarsest levels: there one level pixel spans
//! half an exemplar or more, so two or three coherent pixels already span a period, and every
//! finer level inherits the layout.
//!
//! The test sees only the 3×3 neighbourhood the correction reads anyway (the padding plan is
//! unchanged): candidate `c` at `p` is *coherent* with neighbour `p + Δ` when it lies within
//! [`PERIOD_TOLERANCE`] pixels (toroidal Chebyshev) of `S[p + Δ] − h·Δ`, the coordinate
//! that continues that neighbour's patch. With `E_x` the extent along x of `{0}` and the
//! offsets of the coherent neighbours (0, 1 or 2 level pixels), `c` spans a period when
//! `E_x · h ≥ w` or `E_y · h ≥ H` (`w`×`H` the exemplar, `h` the level spacing). So the test
//! acts at the levels where `2h` reaches a period (the coarsest one or two), never below.
//! The penalty is an integer added to the candidate's distance, identical on the GPU
//! (`glsl/synth/correct.comp`) and here.

use super::coords::{torus_distance, unpack};
use super::neighbourhood::shifted;

/// Largest coordinate distance, in exemplar pixels, at which a candidate counts as continuing a
/// neighbour's patch: the tolerance of the period repetition measure, so that what is
/// penalized is what that measure counts (near-copies shifted by a few pixels included).
pub const PERIOD_TOLERANCE: u32 = crate::shader_constants::SYNTH_PERIOD_TOLERANCE;

const _: () = assert!(PERIOD_TOLERANCE == super::repetition::REPETITION_TOLERANCE);

/// Extent, in level pixels and per axis, that a coherent patch needs to span an exemplar
/// period at `spacing`: `ceil(side / spacing)`, or 0 (never) when that exceeds the 2 that a
/// 3×3 neighbourhood can show.
pub fn period_reach(spacing: u32, width: u32, height: u32) -> [u32; 2] {
    [width, height].map(|side| {
        let reach = side.div_ceil(spacing);
        if reach <= 2 {
            reach
        } else {
            0
        }
    })
}

/// Whether candidate `c` for the centre of the 3×3 coordinates `around` (row by row, index 4
/// the centre) would make its coherent patch span a period (see the module docs); `reach` is
/// [`period_reach`] of the level.
pub fn spans_period(
    c: u32,
    around: &[u32; 9],
    spacing: i32,
    w: u32,
    h: u32,
    reach: [u32; 2],
) -> bool {
    let (mut lo, mut hi) = ([0i32; 2], [0i32; 2]);
    for (n, &s) in around.iter().enumerate() {
        let (dx, dy) = (n as i32 % 3 - 1, n as i32 / 3 - 1);
        if n == 4 {
            continue;
        }
        let continued = shifted(s, -dx, -dy, spacing, w, h);
        if torus_distance(unpack(c), unpack(continued), w, h) <= PERIOD_TOLERANCE {
            for (a, d) in [dx, dy].into_iter().enumerate() {
                lo[a] = lo[a].min(d);
                hi[a] = hi[a].max(d);
            }
        }
    }
    (0..2).any(|a| reach[a] != 0 && (hi[a] - lo[a]) as u32 >= reach[a])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coords::pack;

    #[test]
    fn reach_follows_the_spacing() {
        assert_eq!(period_reach(64, 64, 64), [1, 1]);
        assert_eq!(period_reach(32, 64, 64), [2, 2]);
        assert_eq!(period_reach(16, 64, 64), [0, 0]);
        assert_eq!(period_reach(64, 96, 100), [2, 2]);
        assert_eq!(period_reach(64, 127, 80), [2, 2]);
        assert_eq!(period_reach(32, 127, 80), [0, 0]);
    }

    #[test]
    fn coherent_runs_span_a_period_only_when_wide_enough() {
        let (w, h, s) = (64u32, 64u32, 32i32);
        let reach = period_reach(s as u32, w, h);
        // A fully coherent 3×3 patch around exemplar pixel (10, 20).
        let centre = pack(10, 20);
        let around: [u32; 9] =
            std::array::from_fn(|n| shifted(centre, n as i32 % 3 - 1, n as i32 / 3 - 1, s, w, h));
        assert!(spans_period(centre, &around, s, w, h, reach));
        // Two pixels off by the tolerance still count; one pixel further does not.
        assert!(spans_period(pack(14, 24), &around, s, w, h, reach));
        assert!(!spans_period(pack(15, 20), &around, s, w, h, reach));
        // Coherent with the right-hand neighbour only: extent 1 along x, half a period at
        // spacing 32 (the whole right-hand column would also have extent 2, a period, along y).
        let mut right = [pack(40, 40); 9];
        right[5] = around[5];
        assert!(!spans_period(centre, &right, s, w, h, reach));
        let mut column = right;
        for n in [2, 8] {
            column[n] = around[n];
        }
        assert!(spans_period(centre, &column, s, w, h, reach));
        // At spacing 64 one coherent neighbour is a whole period.
        assert!(spans_period(
            centre,
            &right.map(|c| if c == pack(40, 40) { c } else { centre }),
            64,
            w,
            h,
            period_reach(64, w, h)
        ));
        // Finer levels are never penalized.
        assert!(!spans_period(
            centre,
            &around,
            16,
            w,
            h,
            period_reach(16, w, h)
        ));
    }
}
