//! The baseline: Embark's `texture-synthesis` crate (multiresolution stochastic synthesis on the
//! CPU), run with its defaults except the seed, the output size and the thread count.

use anyhow::Context;
use lazysolid_synth::{pack, Exemplar, MAX_EXEMPLAR_SIDE};
use texture_synthesis::image::{DynamicImage, RgbImage, Rgba, RgbaImage};
use texture_synthesis::{Dims, GeneratedImage, Session};

/// The settings the baseline runs with, as the bench reports them.
pub fn settings(threads: usize) -> String {
    format!(
        "texture-synthesis 0.8.2 defaults (50 nearest neighbours, 50 random sample locations, \
         cauchy dispersion 1.0, backtrack 50% over 5 stages, no tiling mode), \
         max_thread_count {threads}, seed and output size as lazysolid"
    )
}

/// One output of the baseline.
pub struct Output {
    /// RGB pixels, row-major.
    pub rgb: Vec<[u8; 3]>,
    /// The exemplar pixel every output pixel was copied from, packed as lazysolid's
    /// coordinates, so both synthesizers' outputs can be measured for repetition alike.
    pub coords: Vec<u32>,
}

/// Synthesizes a `size`² image from `exemplar`: session build (the example's pyramid) and run,
/// the whole of what a user of the crate waits for (what the bench times).
pub fn synthesize(
    exemplar: &Exemplar,
    size: u32,
    seed: u64,
    threads: usize,
) -> anyhow::Result<GeneratedImage> {
    let bytes: Vec<u8> = exemplar.rgb.iter().flatten().copied().collect();
    let image = RgbImage::from_raw(exemplar.width, exemplar.height, bytes)
        .context("exemplar size does not match its pixels")?;
    let session = Session::builder()
        .add_example(DynamicImage::ImageRgb8(image))
        .output_size(Dims::square(size))
        .seed(seed)
        .max_thread_count(threads)
        .build()
        .map_err(|e| anyhow::anyhow!("texture-synthesis refused the session: {e}"))?;
    Ok(session.run(None))
}

/// The pixels and the coordinate map of a `size`² output of [`synthesize`] (untimed).
pub fn output(generated: GeneratedImage, exemplar: &Exemplar, size: u32) -> anyhow::Result<Output> {
    const _: () = assert!(MAX_EXEMPLAR_SIDE <= 4096, "positions are stored in 12 bits");
    let transform = generated.get_coordinate_transform();
    let out = generated.into_image().to_rgb8();
    anyhow::ensure!(
        out.dimensions() == (size, size),
        "texture-synthesis returned {:?} pixels, expected {size}x{size}",
        out.dimensions()
    );
    // Applying the transform to an image that holds each pixel's own position recovers the
    // source position of every output pixel: the low 8 bits of x and y in red and green, their
    // high 4 bits in blue (exemplars are at most 512 pixels a side).
    let positions = RgbaImage::from_fn(exemplar.width, exemplar.height, |x, y| {
        Rgba([x as u8, y as u8, ((x >> 8) | (y >> 8) << 4) as u8, 255])
    });
    let map = transform
        .apply([DynamicImage::ImageRgba8(positions)])
        .map_err(|e| anyhow::anyhow!("texture-synthesis coordinate transform: {e}"))?;
    Ok(Output {
        rgb: out.pixels().map(|p| p.0).collect(),
        coords: map
            .pixels()
            .map(|p| {
                let [r, g, b, _] = p.0.map(u32::from);
                pack(r | (b & 15) << 8, g | (b >> 4) << 8)
            })
            .collect(),
    })
}
