//! The Gaussian stack of the exemplar: every level is full size (a stack, not a pyramid), level
//! `l` blurred with σ = 2^(L−l)/2 so that its detail matches the coordinate spacing
//! `h_l = 2^(L−l)` at which synthesis level `l` samples it. The finest level is the exemplar.
//!
//! Toroidal exemplars wrap at the borders; others are clamped to the edge pixel (their
//! synthesized coordinates still wrap, so a non-tileable exemplar relies on correction to hide
//! its seams).

use super::exemplar::Exemplar;

/// Index of `i` in `0..n` by wrapping (toroidal) or clamping.
pub(crate) fn border(i: i64, n: u32, toroidal: bool) -> usize {
    if toroidal {
        i.rem_euclid(n as i64) as usize
    } else {
        i.clamp(0, n as i64 - 1) as usize
    }
}

/// One separable pass of a normalized Gaussian of standard deviation `sigma` (pixels).
fn blur_pass(
    src: &[[f32; 3]],
    w: u32,
    h: u32,
    sigma: f32,
    horizontal: bool,
    toroidal: bool,
) -> Vec<[f32; 3]> {
    let radius = (3.0 * sigma).ceil() as i64;
    let weights: Vec<f32> = (-radius..=radius)
        .map(|d| (-((d * d) as f32) / (2.0 * sigma * sigma)).exp())
        .collect();
    let total: f32 = weights.iter().sum();
    let mut out = vec![[0.0f32; 3]; src.len()];
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            let mut acc = [0.0f32; 3];
            for (j, wgt) in weights.iter().enumerate() {
                let d = j as i64 - radius;
                let (sx, sy) = if horizontal {
                    (border(x + d, w, toroidal), y as usize)
                } else {
                    (x as usize, border(y + d, h, toroidal))
                };
                let s = src[sy * w as usize + sx];
                for c in 0..3 {
                    acc[c] += wgt * s[c];
                }
            }
            out[y as usize * w as usize + x as usize] = acc.map(|a| a / total);
        }
    }
    out
}

/// A separable Gaussian blur of standard deviation `sigma` (pixels), rows then columns.
pub(crate) fn gaussian_blur(
    src: &[[f32; 3]],
    w: u32,
    h: u32,
    sigma: f32,
    toroidal: bool,
) -> Vec<[f32; 3]> {
    let rows = blur_pass(src, w, h, sigma, true, toroidal);
    blur_pass(&rows, w, h, sigma, false, toroidal)
}

/// Levels `0..=finest` of the stack of `base`: level `l` blurred with σ = 2^(finest−l)/2.
fn stack_of(
    base: Vec<[f32; 3]>,
    w: u32,
    h: u32,
    finest: u32,
    toroidal: bool,
) -> Vec<Vec<[f32; 3]>> {
    let mut levels: Vec<Vec<[f32; 3]>> = (0..finest)
        .map(|level| {
            let sigma = (1u32 << (finest - level)) as f32 / 2.0;
            gaussian_blur(&base, w, h, sigma, toroidal)
        })
        .collect();
    levels.push(base);
    levels
}

/// Levels `0..=L` (coarsest first) of the exemplar's Gaussian stack, colours in 0..=255.
pub fn gaussian_stack(exemplar: &Exemplar, toroidal: bool) -> Vec<Vec<[f32; 3]>> {
    let base: Vec<[f32; 3]> = exemplar.rgb.iter().map(|p| p.map(f32::from)).collect();
    stack_of(
        base,
        exemplar.width,
        exemplar.height,
        exemplar.finest_level(),
        toroidal,
    )
}

/// Levels `0..=finest` (coarsest first) of the Gaussian stack of a scalar `w`×`h` channel
/// (the feature distance), blurred exactly as [`gaussian_stack`] blurs the colours.
pub fn scalar_stack(channel: &[f32], w: u32, h: u32, finest: u32, toroidal: bool) -> Vec<Vec<f32>> {
    let base: Vec<[f32; 3]> = channel.iter().map(|&v| [v, 0.0, 0.0]).collect();
    stack_of(base, w, h, finest, toroidal)
        .into_iter()
        .map(|level| level.into_iter().map(|p| p[0]).collect())
        .collect()
}
