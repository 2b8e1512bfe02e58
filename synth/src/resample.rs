//! Lanczos3 resampling of an RGB image that can wrap at its borders.
//!
//! The synthesizers read an exemplar as a torus (coordinates modulo its sides), so an
//! exemplar resampled by a filter that clamps at the borders, as general-purpose resizers
//! do, would gain a seam where a tileable pattern had none: near an edge the clamped filter
//! repeats the edge pixel where the synthesizer continues with the opposite edge. This filter
//! reads past an edge from the opposite one ([`Border::Wrap`]) or from the edge pixel
//! ([`Border::Clamp`], for exemplars synthesized with clamped borders).
//!
//! The kernel is the usual Lanczos3 `sinc(x) · sinc(x / 3)` on `|x| < 3`, widened by the
//! reduction factor when shrinking (so it also removes what the smaller image cannot hold),
//! applied separably with normalized weights in `f32`, and rounded once at the end. Every
//! output pixel sums its taps in a fixed order, so the result is the same on every run: the
//! disk caches key on it.

use rayon::prelude::*;

/// What the filter reads beyond an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Border {
    /// The opposite edge (the image tiles).
    Wrap,
    /// The edge pixel.
    Clamp,
}

/// Lanczos3 weight at distance `x` (in kernel units).
fn lanczos3(x: f64) -> f64 {
    let sinc = |t: f64| {
        if t.abs() < 1e-9 {
            1.0
        } else {
            let p = std::f64::consts::PI * t;
            p.sin() / p
        }
    };
    if x.abs() >= 3.0 {
        0.0
    } else {
        sinc(x) * sinc(x / 3.0)
    }
}

/// For each of `dst` output samples along an axis of `src` input samples: the source indices
/// (already wrapped or clamped) and their normalized weights.
fn taps(src: u32, dst: u32, border: Border) -> Vec<Vec<(usize, f32)>> {
    let ratio = src as f64 / dst as f64;
    let scale = ratio.max(1.0);
    let support = 3.0 * scale;
    (0..dst)
        .map(|i| {
            let centre = (i as f64 + 0.5) * ratio - 0.5;
            let first = (centre - support).floor() as i64 + 1;
            let last = (centre + support).ceil() as i64 - 1;
            let raw: Vec<(i64, f64)> = (first..=last)
                .map(|j| (j, lanczos3((j as f64 - centre) / scale)))
                .filter(|&(_, w)| w != 0.0)
                .collect();
            let total: f64 = raw.iter().map(|&(_, w)| w).sum();
            raw.into_iter()
                .map(|(j, w)| {
                    let index = match border {
                        Border::Wrap => j.rem_euclid(src as i64),
                        Border::Clamp => j.clamp(0, src as i64 - 1),
                    };
                    (index as usize, (w / total) as f32)
                })
                .collect()
        })
        .collect()
}

/// Resamples the `width`×`height` image `rgb` (row-major) to `new_width`×`new_height`.
/// Sides must be at least 1; the same size returns the pixels unchanged.
pub fn resample_lanczos3(
    rgb: &[[u8; 3]],
    width: u32,
    height: u32,
    new_width: u32,
    new_height: u32,
    border: Border,
) -> Vec<[u8; 3]> {
    debug_assert_eq!(rgb.len(), (width * height) as usize);
    if (width, height) == (new_width, new_height) {
        return rgb.to_vec();
    }
    let sums = filter(
        |i| rgb[i].map(f32::from),
        [width, height],
        [new_width, new_height],
        border,
    );
    sums.into_iter()
        .map(|acc| acc.map(|v| v.round().clamp(0.0, 255.0) as u8))
        .collect()
}

/// [`resample_lanczos3`] for samples that are not colours (normals, heights): `C` channels
/// of `f32` per pixel, filtered alike and returned unrounded and unclamped (Lanczos3 may
/// overshoot the input's range near an edge).
pub fn resample_lanczos3_f32<const C: usize>(
    samples: &[[f32; C]],
    width: u32,
    height: u32,
    new_width: u32,
    new_height: u32,
    border: Border,
) -> Vec<[f32; C]> {
    debug_assert_eq!(samples.len(), (width * height) as usize);
    if (width, height) == (new_width, new_height) {
        return samples.to_vec();
    }
    filter(
        |i| samples[i],
        [width, height],
        [new_width, new_height],
        border,
    )
}

/// The separable filter of both resamplers: rows first (`height` rows of the new width), then
/// columns, each output summing its taps in a fixed order.
fn filter<const C: usize>(
    sample: impl Fn(usize) -> [f32; C] + Sync,
    [width, height]: [u32; 2],
    [new_width, new_height]: [u32; 2],
    border: Border,
) -> Vec<[f32; C]> {
    let across = taps(width, new_width, border);
    let down = taps(height, new_height, border);
    let (w, nw) = (width as usize, new_width as usize);
    let mut rows = vec![[0.0f32; C]; nw * height as usize];
    rows.par_chunks_mut(nw).enumerate().for_each(|(y, out)| {
        for (o, t) in out.iter_mut().zip(&across) {
            for &(j, wgt) in t {
                let s = sample(y * w + j);
                for c in 0..C {
                    o[c] += wgt * s[c];
                }
            }
        }
    });
    let mut out = vec![[0.0f32; C]; nw * new_height as usize];
    out.par_chunks_mut(nw).zip(&down).for_each(|(line, t)| {
        for (x, o) in line.iter_mut().enumerate() {
            for &(j, wgt) in t {
                let s = rows[j * nw + x];
                for c in 0..C {
                    o[c] += wgt * s[c];
                }
            }
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_indices_stay_inside() {
        for (src, dst) in [(100, 128), (144, 128), (8192, 256), (16, 32), (115, 128)] {
            for border in [Border::Wrap, Border::Clamp] {
                for t in taps(src, dst, border) {
                    let total: f32 = t.iter().map(|&(_, w)| w).sum();
                    assert!((total - 1.0).abs() < 1e-5, "{src}->{dst}: {total}");
                    assert!(t.iter().all(|&(j, _)| j < src as usize));
                }
            }
        }
    }

    #[test]
    fn a_constant_stays_constant_and_the_same_size_is_unchanged() {
        let grey = vec![[90u8, 120, 200]; 37 * 23];
        for border in [Border::Wrap, Border::Clamp] {
            let out = resample_lanczos3(&grey, 37, 23, 64, 16, border);
            assert_eq!(out.len(), 64 * 16);
            assert!(out.iter().all(|&p| p == [90, 120, 200]), "{border:?}");
        }
        let ramp: Vec<[u8; 3]> = (0..20 * 20).map(|i| [i as u8, 0, 255]).collect();
        assert_eq!(resample_lanczos3(&ramp, 20, 20, 20, 20, Border::Wrap), ramp);
    }

    #[test]
    fn wrapping_keeps_a_tiling_pattern_periodic_where_clamping_does_not() {
        // Vertical stripes of period 4 across a 100-pixel row, whose last stripe runs into
        // the first: resampled to 50 with wrapping, the stripes of period 2 continue across
        // the edge; clamped, the edge columns differ from the inner ones.
        let (w, h) = (100u32, 4u32);
        let rgb: Vec<[u8; 3]> = (0..w * h)
            .map(|i| if (i % w) % 4 < 2 { [200; 3] } else { [40; 3] })
            .collect();
        let wrapped = resample_lanczos3(&rgb, w, h, 50, 4, Border::Wrap);
        let inner = wrapped[10];
        let inner_next = wrapped[11];
        assert_eq!(wrapped[0], inner);
        assert_eq!(wrapped[49], inner_next);
        let clamped = resample_lanczos3(&rgb, w, h, 50, 4, Border::Clamp);
        assert_eq!(clamped[10], inner);
        assert_ne!(clamped[49], inner_next);
    }
}
