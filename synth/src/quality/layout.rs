//! Layout repetition: how much the large structures of an image repeat at the exemplar's
//! period, read from the pixels alone.
//!
//! The period repetition (`repetition.rs`) compares exemplar coordinates one period apart with
//! a tolerance of 4 pixels, so it counts copies of the fine detail. A synthesizer can lay out
//! the exemplar's large structures as a grid (a shifted copy per block of the coarsest level)
//! and then re-synthesize the detail inside them: the coordinates no longer repeat, the eye
//! still sees the grid at once (cracked 144² → 512², period repetition 0.234 with its plates
//! in rows and columns, `docs/synthesis.md`). This figure looks at the structures instead:
//! the luminance at the octave of the Gaussian pyramid where one exemplar period spans about
//! [`PERIOD_PIXELS`] pixels (the scale the coarse levels decide), and the correlation of that
//! image with itself one period to the right and one period down. A tiling scores 1; a layout
//! of independently placed structures scores near 0; it needs no coordinate map, so any
//! synthesizer's output, or a slice of a volume, is scored the same way.

use super::image::LinearImage;

/// Pixels that one exemplar period spans at the octave the figure is read at.
pub const PERIOD_PIXELS: usize = 16;

/// The correlation, in [-1, 1], of the image's coarse luminance with itself shifted by one
/// exemplar period (`period_width` to the right, `period_height` down; pairs inside the
/// image only). 0 when no pair fits or the coarse image is flat.
pub fn layout_repetition(image: &LinearImage, period_width: usize, period_height: usize) -> f64 {
    let period = period_width.min(period_height).max(1);
    let octave = (period / PERIOD_PIXELS).max(1).ilog2() as usize;
    let coarse = image.pyramid(octave + 1).pop().expect("one octave");
    let scale = (1usize << octave) as f64;
    let lag_x = (period_width as f64 / scale).round() as usize;
    let lag_y = (period_height as f64 / scale).round() as usize;
    let (w, h) = (coarse.width, coarse.height);
    let lum = coarse.luminance();
    let mean = lum.iter().map(|&v| f64::from(v)).sum::<f64>() / lum.len().max(1) as f64;
    let at = |x: usize, y: usize| f64::from(lum[y * w + x]) - mean;
    let (mut product, mut a2, mut b2) = (0.0, 0.0, 0.0);
    let mut pair = |a: f64, b: f64| {
        product += a * b;
        a2 += a * a;
        b2 += b * b;
    };
    for y in 0..h {
        for x in 0..w {
            if lag_x > 0 && x + lag_x < w {
                pair(at(x, y), at(x + lag_x, y));
            }
            if lag_y > 0 && y + lag_y < h {
                pair(at(x, y), at(x, y + lag_y));
            }
        }
    }
    if a2 <= 0.0 || b2 <= 0.0 {
        0.0
    } else {
        product / (a2 * b2).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `side`² exemplar of random blobs: noise smoothed at a few pixels.
    fn blobs(side: usize, seed: u32) -> LinearImage {
        let mut state = seed.max(1);
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state % 1000) as f32 / 1000.0
        };
        let noise: Vec<f32> = (0..side * side).map(|_| next()).collect();
        let r = 3i64;
        let pixels = (0..side * side)
            .map(|i| {
                let (x, y) = ((i % side) as i64, (i / side) as i64);
                let mut s = 0.0;
                for dy in -r..=r {
                    for dx in -r..=r {
                        let (u, v) = (
                            (x + dx).rem_euclid(side as i64),
                            (y + dy).rem_euclid(side as i64),
                        );
                        s += noise[v as usize * side + u as usize];
                    }
                }
                let v = s / ((2 * r + 1) * (2 * r + 1)) as f32;
                [v; 3]
            })
            .collect();
        LinearImage {
            width: side,
            height: side,
            pixels,
        }
    }

    /// A `size`² output made of `block`² blocks, each the exemplar read from an offset that
    /// `offset(bx, by)` gives.
    fn layout(
        exemplar: &LinearImage,
        size: usize,
        block: usize,
        offset: impl Fn(usize, usize) -> (usize, usize),
    ) -> LinearImage {
        let side = exemplar.width;
        let pixels = (0..size * size)
            .map(|i| {
                let (x, y) = (i % size, i / size);
                let (ox, oy) = offset(x / block, y / block);
                exemplar.pixels[((y + oy) % side) * side + (x + ox) % side]
            })
            .collect();
        LinearImage {
            width: size,
            height: size,
            pixels,
        }
    }

    #[test]
    fn tilings_score_one_and_independent_layouts_near_zero() {
        let side = 128;
        let e = blobs(side, 7);
        let tiling = layout(&e, 512, 512, |_, _| (0, 0));
        let t = layout_repetition(&tiling, side, side);
        assert!(t > 0.99, "tiling {t}");
        // Blocks of the exemplar's size, each shifted at random: the grid of shifted copies
        // that a synthesizer makes when its coarsest level is the layout.
        let hash = |a: usize, b: usize| ((a * 7919 + b * 104_729 + 13) * 2_654_435_761) % side;
        let shifted = layout(&e, 512, side, |bx, by| (hash(bx, by), hash(by + 5, bx + 3)));
        let s = layout_repetition(&shifted, side, side);
        // Blocks of a quarter period, each shifted at random: no structure repeats.
        let mixed = layout(&e, 512, side / 4, |bx, by| {
            (hash(bx, by), hash(by + 5, bx + 3))
        });
        let m = layout_repetition(&mixed, side, side);
        assert!(s.abs() < 0.2 && m.abs() < 0.2, "shifted {s}, mixed {m}");
        // Every block the same small shift from its neighbours: a near-tiling still repeats.
        let near = layout(&e, 512, side, |bx, by| ((bx * 3) % side, (by * 2) % side));
        let n = layout_repetition(&near, side, side);
        assert!(n > 0.6, "near-tiling {n}");
        // Too small an output for one period: nothing to compare.
        let small = layout(&e, 100, 100, |_, _| (0, 0));
        assert_eq!(layout_repetition(&small, side, side), 0.0);
    }
}
