//! The examples every part measures: the `--exemplar` image (the assets' exemplars or a path,
//! a GIMP pattern or a PNG) read as a height map (luminance times `--relief` texels) and cropped
//! to N² where it is at least that large; sizes the image lacks use a deterministic generated
//! height field of bumps and scratches. The table's case names say which. Kept apart so that
//! every part reads the same example for a size.

use super::GlintsArgs;
use crate::cli::assets;
use anyhow::Context;
use lazysolid_renderer::glint::synthetic::{bumps_and_scratches, BumpExtent};
use lazysolid_renderer::glint::NormalExample;
use lazysolid_synth::Exemplar;

/// An example and where it came from.
pub(super) struct Example {
    pub(super) example: NormalExample,
    pub(super) source: String,
}

/// The height map image: its luminance (0..1), row by row.
pub(super) struct HeightImage {
    name: String,
    width: usize,
    height: usize,
    luma: Vec<f32>,
}

/// The `--exemplar` image, or `None` for `generated`.
pub(super) fn load_image(args: &GlintsArgs) -> anyhow::Result<Option<HeightImage>> {
    if args.exemplar == "generated" {
        return Ok(None);
    }
    let path = assets::exemplar(
        "--exemplar",
        &args.exemplar,
        args.exemplar_dir.path.as_deref(),
    )?;
    let is_pat = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("pat"));
    let (w, h, luma) = if is_pat {
        let e = Exemplar::load(&path)
            .with_context(|| format!("loading --exemplar {}", path.display()))?;
        let luma = e
            .rgb
            .iter()
            .map(|p| (0.299 * p[0] as f32 + 0.587 * p[1] as f32 + 0.114 * p[2] as f32) / 255.0)
            .collect();
        (e.width as usize, e.height as usize, luma)
    } else {
        let img = image::open(&path)
            .with_context(|| format!("loading --exemplar {}", path.display()))?
            .to_luma32f();
        let (w, h) = img.dimensions();
        (w as usize, h as usize, img.into_raw())
    };
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| args.exemplar.clone());
    Ok(Some(HeightImage {
        name,
        width: w,
        height: h,
        luma,
    }))
}

/// The example of edge `size`: the image cropped (top left) where it is large enough, the
/// generated field otherwise.
pub(super) fn example_of(
    size: usize,
    image: Option<&HeightImage>,
    args: &GlintsArgs,
) -> anyhow::Result<Example> {
    match image {
        Some(HeightImage {
            name,
            width: w,
            height: h,
            luma,
        }) if *w >= size && *h >= size => {
            let heights: Vec<f32> = (0..size * size)
                .map(|i| luma[(i / size) * w + i % size] * args.relief)
                .collect();
            let source = if *w == size && *h == size {
                format!("{name} {w}x{h} as heights x{}", args.relief)
            } else {
                format!(
                    "{name} {w}x{h} cropped to {size}² as heights x{}",
                    args.relief
                )
            };
            Ok(Example {
                example: NormalExample::from_heights(name, size, &heights)?,
                source,
            })
        }
        _ => {
            let source = format!("generated bumps and scratches, seed {}", args.seed);
            Ok(Example {
                example: NormalExample::from_heights(
                    &source,
                    size,
                    &bumps_and_scratches(size, args.seed, BumpExtent::FourSigma),
                )?,
                source,
            })
        }
    }
}

/// Short label of an example's source for case names.
pub(super) fn short_source(e: &Example, image: Option<&HeightImage>) -> String {
    match image {
        Some(i) if e.source.starts_with(i.name.as_str()) => i.name.clone(),
        _ => "generated".into(),
    }
}
