//! The CPU twin of `glsl/include/render/image.glsl`: the same wrap, bilinear, trilinear and
//! anisotropic lookup in the same order of operations, so the kernel can be checked against it.

use super::pyramid::{level_size, srgb_to_linear, unpack};
use super::{ImageEncoding, ImageTexture};
use crate::shader_constants::IMAGE_MAX_ANISOTROPY;
use glam::{Vec2, Vec4};
use lazysolid_compute::ctree::colour::ColourTrees;

/// Texel (x, y) of level `l` (wrapped), decoded: linear colour and alpha, or the normal's xyz
/// (w = 1).
pub fn fetch(image: &ImageTexture, l: usize, x: i32, y: i32) -> Vec4 {
    let (w, h) = level_size(image.width, image.height, l);
    let xi = x.rem_euclid(w as i32) as u32;
    let yi = y.rem_euclid(h as i32) as u32;
    fetch_linear(image, image.levels[l][(yi * w + xi) as usize])
}

/// A packed texel of `image` decoded: linear colour and alpha, or the normal's xyz (w = 1).
pub fn fetch_linear(image: &ImageTexture, texel: u32) -> Vec4 {
    let c = unpack(texel);
    match image.encoding {
        ImageEncoding::SrgbColor => Vec4::new(
            srgb_to_linear(c.x),
            srgb_to_linear(c.y),
            srgb_to_linear(c.z),
            c.w,
        ),
        ImageEncoding::Normal => Vec4::new(c.x * 2.0 - 1.0, c.y * 2.0 - 1.0, c.z * 2.0 - 1.0, 1.0),
    }
}

/// Bilinear lookup of level `l` at texture coordinates `uv` (v up: v = 1 is row 0), repeating.
pub fn bilinear(image: &ImageTexture, l: usize, uv: Vec2) -> Vec4 {
    let (w, h) = level_size(image.width, image.height, l);
    let x = uv.x * w as f32 - 0.5;
    let y = (1.0 - uv.y) * h as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let (x0, y0) = (x0 as i32, y0 as i32);
    let a = fetch(image, l, x0, y0) * (1.0 - fx) + fetch(image, l, x0 + 1, y0) * fx;
    let b = fetch(image, l, x0, y0 + 1) * (1.0 - fx) + fetch(image, l, x0 + 1, y0 + 1) * fx;
    a * (1.0 - fy) + b * fy
}

/// Trilinear lookup at a fractional level (clamped to the pyramid).
pub fn trilinear(image: &ImageTexture, uv: Vec2, lod: f32) -> Vec4 {
    let top = (image.levels.len() - 1) as f32;
    let lod = lod.clamp(0.0, top);
    let l0 = lod.floor();
    let f = lod - l0;
    let a = bilinear(image, l0 as usize, uv);
    if f > 0.0 {
        a * (1.0 - f) + bilinear(image, l0 as usize + 1, uv) * f
    } else {
        a
    }
}

/// One tap of a tree-coded image (`image_ctree` in GLSL): each YCoCg channel through its tree
/// at (u, 1 − v) wrapped and level `lod`, rounded (halves up), the exact integer inverse of
/// YCoCg-R, then sRGB decoded; alpha 1.
pub fn ctree_tap(trees: &ColourTrees, uv: Vec2, lod: f32) -> Vec4 {
    let p = [uv.x - uv.x.floor(), 1.0 - (uv.y - uv.y.floor()), 0.0];
    let [y, co, cg] = trees
        .channels
        .each_ref()
        .map(|t| (t.sample(p, lod) + 0.5).floor() as i32);
    let s = y - (cg >> 1);
    let g = cg + s;
    let b = s - (co >> 1);
    let r = b + co;
    let c = [r, g, b].map(|v| srgb_to_linear(v.clamp(0, 255) as f32 / 255.0));
    Vec4::new(c[0], c[1], c[2], 1.0)
}

/// [`lookup`] of a tree-coded image: the same taps, each read through the trees.
pub fn lookup_ctree(image: &ImageTexture, trees: &ColourTrees, uv: Vec2, a: Vec2, b: Vec2) -> Vec4 {
    let (lod, n, axis) = footprint_taps(image, a, b);
    let mut sum = Vec4::ZERO;
    for k in 0..n {
        let t = (k as f32 + 0.5) / n as f32 - 0.5;
        sum += ctree_tap(trees, uv + axis * t, lod);
    }
    sum / n as f32
}

/// The level and taps of an anisotropic lookup whose footprint has the axes `a` and `b`
/// (texture-coordinate units): up to [`IMAGE_MAX_ANISOTROPY`] trilinear taps spread along the
/// long axis, at the level of the short axis (or of the long one over the taps, if larger).
pub fn footprint_taps(image: &ImageTexture, a: Vec2, b: Vec2) -> (f32, u32, Vec2) {
    let size = Vec2::new(image.width as f32, image.height as f32);
    let (la, lb) = ((a * size).length(), (b * size).length());
    let (major, minor, axis) = if la >= lb { (la, lb, a) } else { (lb, la, b) };
    let n = (major / minor.max(1e-6))
        .ceil()
        .clamp(1.0, IMAGE_MAX_ANISOTROPY as f32);
    let lod = (major / n).max(minor).max(1e-6).log2();
    (lod, n as u32, axis)
}

/// The filtered value over a footprint with axes `a`, `b` centred at `uv`.
pub fn lookup(image: &ImageTexture, uv: Vec2, a: Vec2, b: Vec2) -> Vec4 {
    let (lod, n, axis) = footprint_taps(image, a, b);
    let mut sum = Vec4::ZERO;
    for k in 0..n {
        let t = (k as f32 + 0.5) / n as f32 - 0.5;
        sum += trilinear(image, uv + axis * t, lod);
    }
    sum / n as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glint::NormalExample;

    fn checker() -> ImageTexture {
        // 4x4, texel (x, y) bright when x + y is even.
        let texels = (0..16)
            .map(|i| {
                if (i % 4 + i / 4) % 2 == 0 {
                    Vec2::new(0.6, 0.0)
                } else {
                    Vec2::new(-0.6, 0.0)
                }
            })
            .collect();
        let example = NormalExample::from_normals("checker", 8, {
            let t: Vec<Vec2> = texels;
            (0..64).map(|i| t[(i % 8 / 2) + (i / 8 / 2) * 4]).collect()
        })
        .unwrap();
        ImageTexture::from_normals("checker", &example)
    }

    #[test]
    fn texel_centres_read_their_texel_and_v_up_reads_row_zero_at_the_top() {
        let img = checker();
        // Texel (0, 0) is the top-left: u = 0.5/8, v = 1 − 0.5/8.
        let top_left = bilinear(&img, 0, Vec2::new(0.5 / 8.0, 1.0 - 0.5 / 8.0));
        assert!((top_left.x - 0.6).abs() < 0.01, "{top_left}");
        let next = bilinear(&img, 0, Vec2::new(2.5 / 8.0, 1.0 - 0.5 / 8.0));
        assert!((next.x + 0.6).abs() < 0.01, "{next}");
    }

    #[test]
    fn a_wide_footprint_averages_the_checker_away_and_a_narrow_one_keeps_it() {
        let img = checker();
        let uv = Vec2::new(0.5 / 8.0, 1.0 - 0.5 / 8.0);
        let narrow = lookup(
            &img,
            uv,
            Vec2::new(0.5 / 8.0, 0.0),
            Vec2::new(0.0, 0.5 / 8.0),
        );
        assert!((narrow.x - 0.6).abs() < 0.02, "{narrow}");
        let wide = lookup(&img, uv, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0));
        assert!(wide.x.abs() < 0.02, "{wide}");
    }

    #[test]
    fn a_long_thin_footprint_takes_taps_along_its_long_axis_at_the_short_axis_level() {
        let img = checker();
        let (lod, n, axis) =
            footprint_taps(&img, Vec2::new(0.0, 4.0 / 8.0), Vec2::new(1.0 / 8.0, 0.0));
        assert_eq!(n, 4);
        assert!(lod.abs() < 1e-6, "{lod}");
        assert_eq!(axis, Vec2::new(0.0, 0.5));
        let (lod, n, _) =
            footprint_taps(&img, Vec2::new(0.0, 64.0 / 8.0), Vec2::new(1.0 / 8.0, 0.0));
        assert_eq!(n, IMAGE_MAX_ANISOTROPY);
        assert!((lod - 3.0).abs() < 1e-5, "{lod}");
    }
}
