//! Crossbar strips: the `N` samples of a stack level along one image axis, centred on a pixel
//! and spaced by the level's spacing `h` (`N` odd), and their exact integer colour distance.
//! Two roles' neighbourhoods around a candidate triple intersect along such a line, so a
//! consistent triple has similar strips in both images.

use super::analysis::unpack_rgb;

/// Default strip length `N`. The thesis does not give it; 5 matches the 5×5 appearance
/// neighbourhood of the 2D synthesizer (its radius is 2 samples), so a strip covers exactly
/// the line the two neighbourhoods share.
pub const DEFAULT_STRIP: u32 = 5;

/// Longest strip (the GPU keeps a query strip in registers).
pub const MAX_STRIP: u32 = crate::shader_constants::SOLID_MAX_STRIP;

/// Pixel `p` (row-major index) moved by `t` along image axis `axis` on the `m`×`m` torus
/// (`m` a power of two).
pub fn along(p: u32, axis: usize, t: i32, m: u32) -> u32 {
    let (u, v) = (p % m, p / m);
    let mask = m as i32 - 1;
    if axis == 0 {
        v * m + ((u as i32 + t) & mask) as u32
    } else {
        ((v as i32 + t) & mask) as u32 * m + u
    }
}

/// Offset of sample `i` of a strip of `n` samples at spacing `h`.
pub fn sample_offset(i: u32, n: u32, h: u32) -> i32 {
    (i as i32 - (n / 2) as i32) * h as i32
}

/// Squared RGB distance between the strip of `a` at pixel `pa` along `axis_a` and the strip
/// of `b` at `pb` along `axis_b` (exact; at most 11 · 3 · 255² < 2²² per strip).
#[allow(clippy::too_many_arguments)]
pub fn strip_distance(
    a: &[u32],
    pa: u32,
    axis_a: usize,
    b: &[u32],
    pb: u32,
    axis_b: usize,
    n: u32,
    h: u32,
    m: u32,
) -> u32 {
    (0..n)
        .map(|i| {
            let t = sample_offset(i, n, h);
            let ca = unpack_rgb(a[along(pa, axis_a, t, m) as usize]);
            let cb = unpack_rgb(b[along(pb, axis_b, t, m) as usize]);
            ca.iter()
                .zip(cb)
                .map(|(&x, y)| {
                    let d = x as i32 - y as i32;
                    (d * d) as u32
                })
                .sum::<u32>()
        })
        .sum()
}
