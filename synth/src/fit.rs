//! Any image as an exemplar: the rules that turn a decoded image of any size and aspect into
//! the exemplar a synthesizer needs, and an [`ExemplarFit`] that says what was done, printed
//! with every run (`stone.png 200x150 RGB → centre crop 128x128 at (36, 11)`).
//!
//! **2D** ([`fit_plane`]). The 2D synthesizer takes any width and height in
//! [`MIN_EXEMPLAR_SIDE`]..=[`MAX_EXEMPLAR_SIDE`] as they are ("native"): its coordinates live
//! modulo width and height, its pyramid has `floor(log2(min side)) + 1` levels, and its
//! analysis is linear in the pixel count (512² took 45 s on two loaded cores). A larger image
//! is resampled so that its longer side is [`MAX_EXEMPLAR_SIDE`], keeping its aspect; one
//! whose shorter side would then fall under [`MIN_EXEMPLAR_SIDE`] is refused.
//!
//! **Solid** ([`fit_solid`]). The solid synthesizer needs a square with a power-of-two side in
//! [`MIN_SOLID_SIDE`]..=[`MAX_SOLID_SIDE`]: its pyramid halves the side exactly, and each role
//! shares an axis with the others. With [`FitMode::Auto`]:
//! 1. a non-square image is cut to its centre square (the short side): a non-uniform resample
//!    would stretch every structure along one axis;
//! 2. let `p` be the largest power of two at most that side `s` (and at most
//!    [`MAX_SOLID_SIDE`]). When `p ≥ 3/4 · s` the centre `p`² is cut out (144 → 128,
//!    156 → 128, 300 → 256): the structures keep their scale and their pixels, and at most a
//!    quarter of each side is lost;
//! 3. otherwise the square is resampled (Lanczos3) to the power of two nearest `s` in log
//!    scale (`s² < 2p²` → `p`, else `2p`; at most [`MAX_SOLID_SIDE`]): 100 → 128, 115 → 128,
//!    96 → 128, 40 → 32, 200 → 256, 180 → 128, 512 → 256. Structures change scale by at most
//!    √2 (more only above 362 pixels, shrunk to 256), and all of the image is kept.
//!
//! [`FitMode::Crop`] always cuts the centre `p`² (refused under [`MIN_SOLID_SIDE`], where no
//! power of two fits); [`FitMode::Resample`] always resamples the centre square to the nearest
//! power of two. A given side `t` (a power of two in range) replaces `p`: `Auto` cuts when the
//! square holds `t` and `t ≥ 3/4 · s`, and resamples to `t` otherwise; `Crop` cuts and refuses
//! a square under `t`; `Resample` resamples to `t`. Sides under [`MIN_SOLID_SIDE`] are refused
//! in every mode: upsampling a tiny image invents nothing the pyramid could use.
//!
//! Grey, grey+alpha, RGB and RGBA images all load (`decode.rs`): grey is replicated to RGB,
//! alpha is dropped, and the line says so. Resampling wraps at the borders (`resample.rs`),
//! as the synthesizers read the exemplar. The fitted pixels are the exemplar: the analysis
//! and candidate caches key on them, so a photo fitted two ways is two cache entries.

use super::decode::{ChannelLayout, DecodedImage};
use super::error::{SynthError, SynthResult};
use super::exemplar::{Exemplar, MAX_EXEMPLAR_SIDE, MIN_EXEMPLAR_SIDE};
use super::resample::{resample_lanczos3, Border};
use super::solid::{MAX_SOLID_SIDE, MIN_SOLID_SIDE};
use std::fmt;
use std::path::Path;

/// How a solid exemplar is made square with a power-of-two side.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FitMode {
    /// Cut when that loses at most a quarter of the side, resample otherwise (module doc).
    #[default]
    Auto,
    /// Always cut the centre square of the largest power of two that fits.
    Crop,
    /// Always resample the centre square to the nearest power of two.
    Resample,
}

/// A rectangle of the image as read: its top-left corner and size, in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CropRect {
    /// Left column.
    pub x: u32,
    /// Top row.
    pub y: u32,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
}

/// What a fit does to an image of a given size: a centre crop, then a resample, either or
/// both or neither ("native").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FitPlan {
    /// The part kept, when not the whole image.
    pub crop: Option<CropRect>,
    /// The size the kept part is resampled to (Lanczos3), when it changes.
    pub resample: Option<[u32; 2]>,
}

impl FitPlan {
    /// The exemplar's size after the plan, for an image of `width`×`height`.
    pub fn output_size(&self, width: u32, height: u32) -> [u32; 2] {
        match (self.resample, self.crop) {
            (Some(size), _) => size,
            (None, Some(c)) => [c.width, c.height],
            (None, None) => [width, height],
        }
    }
}

/// What was done to turn an image into an exemplar; its `Display` is the one line the
/// commands print, e.g. `stone.png 200x150 RGB → centre crop 128x128 at (36, 11)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExemplarFit {
    /// The file's name (its path's last part), or the in-memory image's name.
    pub name: String,
    /// Width and height as read.
    pub size: [u32; 2],
    /// The channels the file had.
    pub layout: ChannelLayout,
    /// The crop and the resample.
    pub plan: FitPlan,
}

impl ExemplarFit {
    /// Whether the image is used as it is (no crop, no resample).
    pub fn is_native(&self) -> bool {
        self.plan.crop.is_none() && self.plan.resample.is_none()
    }

    /// The exemplar's size.
    pub fn output_size(&self) -> [u32; 2] {
        self.plan.output_size(self.size[0], self.size[1])
    }
}

impl fmt::Display for ExemplarFit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [w, h] = self.size;
        write!(f, "{} {w}x{h} {}", self.name, self.layout)?;
        if self.layout.has_alpha() {
            f.write_str(", alpha dropped")?;
        }
        if self.is_native() {
            return f.write_str(", native");
        }
        if let Some(c) = self.plan.crop {
            write!(
                f,
                " → centre crop {}x{} at ({}, {})",
                c.width, c.height, c.x, c.y
            )?;
        }
        if let Some([rw, rh]) = self.plan.resample {
            write!(f, " → Lanczos3 resample {rw}x{rh}")?;
        }
        Ok(())
    }
}

/// An exemplar and how it was made from its image.
#[derive(Clone, Debug)]
pub struct FittedExemplar {
    /// The exemplar the synthesizer uses.
    pub exemplar: Exemplar,
    /// What was done to the image.
    pub fit: ExemplarFit,
}

/// The centre `side`² of a `width`×`height` image, `None` when that is the whole image.
fn centre_square(width: u32, height: u32, side: u32) -> Option<CropRect> {
    (side != width || side != height).then(|| CropRect {
        x: (width - side) / 2,
        y: (height - side) / 2,
        width: side,
        height: side,
    })
}

/// The largest power of two at most `s` (`s ≥ 1`).
fn floor_power_of_two(s: u32) -> u32 {
    1 << s.ilog2()
}

/// The power of two nearest `s` in log scale: of `p ≤ s < 2p`, `p` when `s < √2 · p`.
fn nearest_power_of_two(s: u32) -> u32 {
    let p = floor_power_of_two(s);
    if (s as u64).pow(2) < 2 * (p as u64).pow(2) {
        p
    } else {
        2 * p
    }
}

/// The automatic rule for a square of side `s` that must become a power of two at most
/// `max_side`: (the side cut out of the image, the side it is resampled to). Cut the largest
/// power of two that fits when that loses at most a quarter of the side, else resample the
/// whole square to the nearest power of two.
fn auto_square(s: u32, max_side: u32) -> (u32, u32) {
    let fits = floor_power_of_two(s).min(max_side);
    if 4 * fits >= 3 * s {
        (fits, fits)
    } else {
        (s, nearest_power_of_two(s).min(max_side))
    }
}

/// The plan that turns a `width`×`height` map (a normal or height map, read as a tile) into
/// the square power-of-two grid from `min_side` to `max_side` texels that its pyramid needs:
/// the solid rule of [`FitMode::Auto`] (module doc) with those limits, so a map is cut or
/// resampled as an exemplar is.
///
/// # Errors
/// A side under `min_side`, named with the limit.
pub fn plan_map(width: u32, height: u32, min_side: u32, max_side: u32) -> Result<FitPlan, String> {
    let s = width.min(height);
    if s < min_side {
        return Err(format!(
            "it is {width}x{height} texels; a map needs at least {min_side} a side (it is \
             fitted to a square power-of-two edge from {min_side} to {max_side}, and upsampling \
             a smaller one invents nothing)"
        ));
    }
    let (cut, to) = auto_square(s, max_side);
    Ok(FitPlan {
        crop: centre_square(width, height, cut),
        resample: (to != cut).then_some([to, to]),
    })
}

/// The plan of the solid rule (module doc) for a `width`×`height` image, optionally to
/// `side`; the error is the limit that refused it.
///
/// # Errors
/// A side under [`MIN_SOLID_SIDE`], a `side` that is not a power of two in range, or a square
/// smaller than `side` under [`FitMode::Crop`].
pub fn plan_solid(
    width: u32,
    height: u32,
    mode: FitMode,
    side: Option<u32>,
) -> Result<FitPlan, String> {
    let s = width.min(height);
    if s < MIN_SOLID_SIDE {
        return Err(format!(
            "solid synthesis needs at least {MIN_SOLID_SIDE} pixels a side (the pyramid's five \
             levels; upsampling a smaller image invents nothing)"
        ));
    }
    if let Some(t) = side {
        if !t.is_power_of_two() || !(MIN_SOLID_SIDE..=MAX_SOLID_SIDE).contains(&t) {
            return Err(format!(
                "the exemplar side asked for, {t}, must be a power of two in \
                 {MIN_SOLID_SIDE}..={MAX_SOLID_SIDE}"
            ));
        }
    }
    let fits = floor_power_of_two(s).min(MAX_SOLID_SIDE);
    let nearest = nearest_power_of_two(s).min(MAX_SOLID_SIDE);
    // (side cut out of the image, side it is resampled to)
    let (cut, to) = match (mode, side) {
        (FitMode::Auto, None) => auto_square(s, MAX_SOLID_SIDE),
        (FitMode::Resample, None) => (s, nearest),
        (FitMode::Crop, None) => (fits, fits),
        (FitMode::Auto, Some(t)) if s >= t && 4 * t >= 3 * s => (t, t),
        (FitMode::Auto, Some(t)) | (FitMode::Resample, Some(t)) => (s, t),
        (FitMode::Crop, Some(t)) if s >= t => (t, t),
        (FitMode::Crop, Some(t)) => {
            return Err(format!(
                "--fit crop cuts a {t}x{t} square out of the image, which needs at least {t} \
                 pixels a side (--fit auto or resample resamples instead)"
            ))
        }
    };
    Ok(FitPlan {
        crop: centre_square(width, height, cut),
        resample: (to != cut).then_some([to, to]),
    })
}

/// The plan of the 2D rule (module doc) for a `width`×`height` image; the error is the limit
/// that refused it.
///
/// # Errors
/// A side under [`MIN_EXEMPLAR_SIDE`], before or after shrinking the longer side to
/// [`MAX_EXEMPLAR_SIDE`].
pub fn plan_plane(width: u32, height: u32) -> Result<FitPlan, String> {
    let too_small = format!(
        "2D synthesis needs at least {MIN_EXEMPLAR_SIDE} pixels a side (the pyramid's five levels)"
    );
    if width.min(height) < MIN_EXEMPLAR_SIDE {
        return Err(too_small);
    }
    let long = width.max(height);
    if long <= MAX_EXEMPLAR_SIDE {
        return Ok(FitPlan {
            crop: None,
            resample: None,
        });
    }
    let shrink =
        |v: u32| ((v as u64 * MAX_EXEMPLAR_SIDE as u64 + long as u64 / 2) / long as u64) as u32;
    let (w, h) = (shrink(width), shrink(height));
    if w.min(h) < MIN_EXEMPLAR_SIDE {
        return Err(format!(
            "{too_small}, and shrinking the longer side to {MAX_EXEMPLAR_SIDE} (the analysis's \
             limit) leaves {w}x{h}: crop it to a less elongated part first"
        ));
    }
    Ok(FitPlan {
        crop: None,
        resample: Some([w, h]),
    })
}

/// The pixels of `rect` in a row-major image `width` pixels wide: the crop of every fit, of
/// exemplars and of maps alike.
pub fn crop<T: Clone>(pixels: &[T], width: u32, rect: CropRect) -> Vec<T> {
    (rect.y..rect.y + rect.height)
        .flat_map(|y| {
            let row = (y * width) as usize;
            pixels[row + rect.x as usize..row + (rect.x + rect.width) as usize].to_vec()
        })
        .collect()
}

/// Applies `plan` to `image`.
fn apply(image: DecodedImage, plan: FitPlan, border: Border) -> SynthResult<FittedExemplar> {
    let name = image.source.file_name().map_or_else(
        || image.source.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let fit = ExemplarFit {
        name,
        size: [image.width, image.height],
        layout: image.layout,
        plan,
    };
    let (mut w, mut h, mut rgb) = (image.width, image.height, image.rgb);
    if let Some(c) = plan.crop {
        rgb = crop(&rgb, w, c);
        (w, h) = (c.width, c.height);
    }
    if let Some([rw, rh]) = plan.resample {
        rgb = resample_lanczos3(&rgb, w, h, rw, rh, border);
        (w, h) = (rw, rh);
    }
    Ok(FittedExemplar {
        exemplar: Exemplar::from_rgb(image.source, w, h, rgb)?,
        fit,
    })
}

/// Fits `image` for solid synthesis by `mode`, optionally to `side` (module doc). Resampling
/// wraps: solid exemplars tile.
///
/// # Errors
/// [`SynthError::Fit`] naming the image and the limit that refused it.
pub fn fit_solid(
    image: DecodedImage,
    mode: FitMode,
    side: Option<u32>,
) -> SynthResult<FittedExemplar> {
    match plan_solid(image.width, image.height, mode, side) {
        Ok(plan) => apply(image, plan, Border::Wrap),
        Err(limit) => Err(refusal(&image, limit)),
    }
}

/// Fits `image` for 2D synthesis (module doc); `border` is how the exemplar is synthesized
/// (wrapping, or clamped with `--clamp`), which a resample follows.
///
/// # Errors
/// [`SynthError::Fit`] naming the image and the limit that refused it.
pub fn fit_plane(image: DecodedImage, border: Border) -> SynthResult<FittedExemplar> {
    match plan_plane(image.width, image.height) {
        Ok(plan) => apply(image, plan, border),
        Err(limit) => Err(refusal(&image, limit)),
    }
}

fn refusal(image: &DecodedImage, limit: String) -> SynthError {
    SynthError::Fit {
        path: image.source.clone(),
        width: image.width,
        height: image.height,
        limit,
    }
}

/// Reads `path` and fits it for solid synthesis ([`fit_solid`]).
///
/// # Errors
/// The image cannot be read ([`DecodedImage::read`]) or fitted.
pub fn load_solid(path: &Path, mode: FitMode, side: Option<u32>) -> SynthResult<FittedExemplar> {
    fit_solid(DecodedImage::read(path)?, mode, side)
}

/// Reads `path` and fits it for 2D synthesis ([`fit_plane`]).
///
/// # Errors
/// The image cannot be read ([`DecodedImage::read`]) or fitted.
pub fn load_plane(path: &Path, border: Border) -> SynthResult<FittedExemplar> {
    fit_plane(DecodedImage::read(path)?, border)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn crop(x: u32, y: u32, side: u32) -> Option<CropRect> {
        Some(CropRect {
            x,
            y,
            width: side,
            height: side,
        })
    }

    /// `(width, height)` under `mode` → (crop, resampled side).
    fn solid(w: u32, h: u32, mode: FitMode, side: Option<u32>) -> (Option<CropRect>, Option<u32>) {
        let plan = plan_solid(w, h, mode, side).unwrap_or_else(|e| panic!("{w}x{h}: {e}"));
        (
            plan.crop,
            plan.resample.map(|[a, b]| {
                assert_eq!(a, b);
                a
            }),
        )
    }

    #[test]
    fn auto_cuts_when_a_quarter_or_less_is_lost_and_resamples_otherwise() {
        let auto = |w, h| solid(w, h, FitMode::Auto, None);
        // Already square powers of two: native.
        for s in [16, 32, 64, 128, 256] {
            assert_eq!(auto(s, s), (None, None), "{s}");
        }
        // Cut: 144 → 128, 156 → 128, 40 → 32, 20 → 16, 300 → 256.
        assert_eq!(auto(144, 144), (crop(8, 8, 128), None));
        assert_eq!(auto(40, 40), (crop(4, 4, 32), None));
        assert_eq!(auto(156, 156), (crop(14, 14, 128), None));
        assert_eq!(auto(20, 20), (crop(2, 2, 16), None));
        assert_eq!(auto(300, 300), (crop(22, 22, 256), None));
        // Resampled to the nearest power of two in log scale.
        for (s, to) in [
            (100, 128),
            (115, 128),
            (96, 128),
            (23, 32),
            (46, 64),
            (180, 128),
            (200, 256),
            (362, 256),
            (512, 256),
            (8192, 256),
        ] {
            assert_eq!(auto(s, s), (None, Some(to)), "{s}");
        }
        // Non-square: the centre square of the short side first, in one crop with a cut.
        assert_eq!(auto(200, 150), (crop(36, 11, 128), None));
        assert_eq!(auto(150, 200), (crop(11, 36, 128), None));
        assert_eq!(auto(137, 99), (crop(19, 0, 99), Some(128)));
        assert_eq!(auto(256, 64), (crop(96, 0, 64), None));
    }

    #[test]
    fn crop_and_resample_modes_and_a_given_side() {
        let c = |w, h| solid(w, h, FitMode::Crop, None);
        assert_eq!(c(100, 100), (crop(18, 18, 64), None));
        assert_eq!(c(200, 150), (crop(36, 11, 128), None));
        assert_eq!(c(1000, 1000), (crop(372, 372, 256), None));
        let r = |w, h| solid(w, h, FitMode::Resample, None);
        assert_eq!(r(144, 144), (None, Some(128)));
        assert_eq!(r(200, 150), (crop(25, 0, 150), Some(128)));
        assert_eq!(r(64, 64), (None, None));
        // To a side: 144 and 100 at 128 (bench solid's case), 128 at 32.
        let auto = |s, t| solid(s, s, FitMode::Auto, Some(t));
        assert_eq!(auto(144, 128), (crop(8, 8, 128), None));
        assert_eq!(auto(100, 128), (None, Some(128)));
        assert_eq!(auto(128, 32), (None, Some(32)));
        assert_eq!(auto(128, 128), (None, None));
        assert_eq!(
            solid(200, 150, FitMode::Auto, Some(32)),
            (crop(25, 0, 150), Some(32))
        );
        assert_eq!(
            solid(128, 128, FitMode::Crop, Some(32)),
            (crop(48, 48, 32), None)
        );
        assert_eq!(
            solid(100, 100, FitMode::Resample, Some(16)),
            (None, Some(16))
        );
    }

    #[test]
    fn what_cannot_be_fitted_is_refused_with_the_limit() {
        for mode in [FitMode::Auto, FitMode::Crop, FitMode::Resample] {
            let e = plan_solid(15, 400, mode, None).unwrap_err();
            assert!(e.contains("at least 16 pixels"), "{e}");
        }
        let e = plan_solid(100, 100, FitMode::Crop, Some(128)).unwrap_err();
        assert!(e.contains("--fit crop") && e.contains("128"), "{e}");
        for bad in [0, 24, 8, 512] {
            let e = plan_solid(100, 100, FitMode::Auto, Some(bad)).unwrap_err();
            assert!(e.contains("power of two in 16..=256"), "{bad}: {e}");
        }
    }

    #[test]
    fn plane_is_native_up_to_512_and_shrinks_beyond_keeping_the_aspect() {
        for (w, h) in [
            (16, 16),
            (100, 100),
            (200, 150),
            (137, 99),
            (512, 512),
            (512, 16),
        ] {
            assert_eq!(
                plan_plane(w, h).unwrap(),
                FitPlan {
                    crop: None,
                    resample: None
                }
            );
        }
        assert_eq!(plan_plane(1024, 768).unwrap().resample, Some([512, 384]));
        assert_eq!(plan_plane(600, 1000).unwrap().resample, Some([307, 512]));
        assert_eq!(plan_plane(8192, 8192).unwrap().resample, Some([512, 512]));
        let e = plan_plane(12, 300).unwrap_err();
        assert!(e.contains("at least 16 pixels"), "{e}");
        let e = plan_plane(4000, 100).unwrap_err();
        assert!(e.contains("512x13"), "{e}");
    }

    /// A `w`×`h` image of a two-axis ramp in memory, as read with `layout`.
    fn image(name: &str, w: u32, h: u32, layout: ChannelLayout) -> DecodedImage {
        let rgb = (0..w * h)
            .map(|i| [(i % w) as u8, (i / w) as u8, 7])
            .collect();
        DecodedImage::from_rgb(name, w, h, rgb, layout).unwrap()
    }

    #[test]
    fn the_line_says_size_channels_crop_and_resample() {
        let f = fit_solid(
            image("dir/stone.png", 200, 150, ChannelLayout::Rgb),
            FitMode::Auto,
            None,
        )
        .unwrap();
        assert_eq!(
            f.fit.to_string(),
            "stone.png 200x150 RGB → centre crop 128x128 at (36, 11)"
        );
        assert_eq!((f.exemplar.width, f.exemplar.height), (128, 128));
        // The crop keeps the pixels: the ramp's value at the crop's corner.
        assert_eq!(f.exemplar.at(0, 0), [36, 11, 7]);
        assert_eq!(f.exemplar.source, Path::new("dir/stone.png"));
        let f = fit_solid(
            image("leaf.png", 100, 100, ChannelLayout::Rgba),
            FitMode::Auto,
            None,
        )
        .unwrap();
        assert_eq!(
            f.fit.to_string(),
            "leaf.png 100x100 RGBA, alpha dropped → Lanczos3 resample 128x128"
        );
        assert_eq!(f.exemplar.rgb.len(), 128 * 128);
        let f = fit_solid(
            image("wide.png", 200, 120, ChannelLayout::GreyAlpha),
            FitMode::Resample,
            None,
        )
        .unwrap();
        assert_eq!(
            f.fit.to_string(),
            "wide.png 200x120 grey+alpha, alpha dropped → centre crop 120x120 at (40, 0) → Lanczos3 resample 128x128"
        );
        let f = fit_plane(
            image("slate.pat", 137, 99, ChannelLayout::Grey),
            Border::Wrap,
        )
        .unwrap();
        assert_eq!(f.fit.to_string(), "slate.pat 137x99 grey, native");
        assert!(f.fit.is_native());
        assert_eq!(f.fit.output_size(), [137, 99]);
        let f = fit_plane(
            image("big.png", 1024, 600, ChannelLayout::Rgb),
            Border::Clamp,
        )
        .unwrap();
        assert_eq!(
            f.fit.to_string(),
            "big.png 1024x600 RGB → Lanczos3 resample 512x300"
        );
        assert_eq!((f.exemplar.width, f.exemplar.height), (512, 300));
    }

    #[test]
    fn a_refusal_names_the_image_its_size_and_the_limit() {
        let e = fit_solid(
            image("tiny.png", 12, 40, ChannelLayout::Rgb),
            FitMode::Auto,
            None,
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                SynthError::Fit {
                    width: 12,
                    height: 40,
                    ..
                }
            ),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(
            msg.contains("tiny.png") && msg.contains("12x40") && msg.contains("16"),
            "{msg}"
        );
        let msg = fit_plane(image("thin.png", 8, 100, ChannelLayout::Grey), Border::Wrap)
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("thin.png") && msg.contains("at least 16"),
            "{msg}"
        );
    }
}
