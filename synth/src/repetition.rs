//! Period repetition: the share of output pixels that repeat the exemplar at exactly its own
//! period. The neighbourhood energy rewards verbatim copying (the plain tiling of a toroidal
//! exemplar scores 0), so a synthesizer can lower it by drifting towards the tiling; this
//! measure shows that drift. It compares exemplar coordinates, so it needs the coordinate map
//! of an output (lazysolid's, or one recovered from another synthesizer).
//!
//! Two pixels one period apart "repeat" when their exemplar coordinates lie within
//! [`REPETITION_TOLERANCE`] pixels of each other (toroidal Chebyshev distance): near-tilings,
//! whose copies are shifted by a few pixels from block to block, repeat as visibly as the exact
//! tiling. Independently placed patches repeat by chance only: (2t + 1)² / (w h) of the pairs,
//! 2 % for a 64² exemplar.

use super::coords::{torus_distance, unpack};

/// Largest coordinate distance, in exemplar pixels, of two pixels that repeat each other.
pub const REPETITION_TOLERANCE: u32 = 4;

/// Share, in [0, 1], of the pixel pairs one exemplar width apart horizontally or one exemplar
/// height apart vertically (both inside the `width`×`height` output) whose exemplar
/// coordinates repeat (see the module docs). 1 for the plain tiling. 0 when no such pair fits
/// in the output.
pub fn period_repetition(
    coords: &[u32],
    width: u32,
    height: u32,
    exemplar_width: u32,
    exemplar_height: u32,
) -> f64 {
    let (w, h) = (width as usize, height as usize);
    let (ew, eh) = (exemplar_width as usize, exemplar_height as usize);
    debug_assert_eq!(coords.len(), w * h);
    let repeats = |a: u32, b: u32| {
        torus_distance(unpack(a), unpack(b), exemplar_width, exemplar_height)
            <= REPETITION_TOLERANCE
    };
    let mut pairs = 0u64;
    let mut equal = 0u64;
    for y in 0..h {
        for x in 0..w {
            let c = coords[y * w + x];
            if x + ew < w {
                pairs += 1;
                equal += u64::from(repeats(coords[y * w + x + ew], c));
            }
            if y + eh < h {
                pairs += 1;
                equal += u64::from(repeats(coords[(y + eh) * w + x], c));
            }
        }
    }
    if pairs == 0 {
        0.0
    } else {
        equal as f64 / pairs as f64
    }
}
