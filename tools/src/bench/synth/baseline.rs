//! The baseline: Embark's `texture-synthesis` crate (multiresolution stochastic synthesis on the
//! CPU), run with its defaults except the seed, the output size and the thread count.

use anyhow::Context;
use lazysolid_compute::synth::Exemplar;
use texture_synthesis::image::{DynamicImage, RgbImage};
use texture_synthesis::{Dims, Session};

/// The settings the baseline runs with, as the bench reports them.
pub fn settings(threads: usize) -> String {
    format!(
        "texture-synthesis 0.8.2 defaults (50 nearest neighbours, 50 random sample locations, \
         cauchy dispersion 1.0, backtrack 50% over 5 stages, no tiling mode), \
         max_thread_count {threads}, seed and output size as lazysolid"
    )
}

/// Synthesizes a `size`² image from `exemplar`: session build (the example's pyramid) and run,
/// the whole of what a user of the crate waits for. Returns the RGB pixels, row-major.
pub fn synthesize(
    exemplar: &Exemplar,
    size: u32,
    seed: u64,
    threads: usize,
) -> anyhow::Result<Vec<[u8; 3]>> {
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
    let out = session.run(None).into_image().to_rgb8();
    anyhow::ensure!(
        out.dimensions() == (size, size),
        "texture-synthesis returned {:?} pixels, expected {size}x{size}",
        out.dimensions()
    );
    Ok(out.pixels().map(|p| p.0).collect())
}
