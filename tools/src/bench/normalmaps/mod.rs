//! `lazysolid bench normalmaps`: normal maps seen from near to far (seed 000 ch. 7). Two parts
//! join one run:
//!
//! - `quality`: each scene (the receding bumpy plane and the V-groove plane of
//!   `scenes/normal-maps/`) rendered with its normal map unfiltered, plain-MIP filtered and vMF
//!   filtered at a few samples per pixel, against a reference (the unfiltered map at many
//!   samples per pixel): FLIP over the image and the mean relative error and bias in the far
//!   field (pixels whose primary hit is farther than `--far-distance`), where plain MIP fails.
//! - `fit`: the vMF pyramid's EM fit time on the CPU (every core, f64) and on the device (f32,
//!   each level's starts chosen on the host) and its memory against the plain MIP, per map size
//!   and lobe count.

mod fit;
mod quality;

use super::harness::Bench;
use super::CommonArgs;
use crate::cli::resolution::Resolution;
use crate::cli::GlobalArgs;
use clap::Args;
use std::path::PathBuf;

/// What to measure.
#[derive(Args)]
pub struct NormalMapsArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Scenes with one normal-mapped material each (its `normal_filter` is replaced by each
    /// filter in turn).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "scenes/normal-maps/receding-plane.toml,scenes/normal-maps/v-groove.toml,scenes/normal-maps/sphere.toml"
    )]
    pub scenes: Vec<PathBuf>,
    /// Image size of every render.
    #[arg(long, value_name = "WxH", default_value = "320x240")]
    pub res: Resolution,
    /// Samples per pixel of the filtered renders, one set of rows each.
    #[arg(long, value_delimiter = ',', default_value = "1,4,16")]
    pub spp: Vec<u32>,
    /// Samples per pixel of the reference (the unfiltered map).
    #[arg(long, default_value_t = 256)]
    pub reference_spp: u32,
    /// Distance along the camera ray beyond which a pixel is far field (scene units).
    #[arg(long, default_value_t = 12.0)]
    pub far_distance: f32,
    /// Normal-map edges whose vMF fit is timed (powers of two, 8 to 2048).
    #[arg(long, value_delimiter = ',', default_value = "128,256,512")]
    pub fit_sizes: Vec<usize>,
    /// Lobes per texel of the timed fits.
    #[arg(long, value_delimiter = ',', default_value = "4,6")]
    pub lobes: Vec<usize>,
    /// Seed of the generated maps of the fit part.
    #[arg(long, default_value_t = 29)]
    pub seed: u64,
}

/// Runs both parts.
pub fn run(args: &NormalMapsArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    args.res.check("--res", 1..=4096)?;
    anyhow::ensure!(!args.spp.is_empty(), "--spp: give at least one count");
    for &s in args.spp.iter().chain([&args.reference_spp]) {
        anyhow::ensure!((1..=65536).contains(&s), "--spp {s}: must lie in 1..=65536");
    }
    anyhow::ensure!(
        args.far_distance.is_finite() && args.far_distance > 0.0,
        "--far-distance {}: must be a positive distance",
        args.far_distance
    );
    fit::check(args)?;
    let scenes = quality::load_scenes(args)?;
    super::plot::ensure_font()?;
    let gpu = global.gpu()?;
    let cases = (2 * args.fit_sizes.len() * args.lobes.len()) as u64;
    let mut bench = Bench::new("bench normalmaps", &gpu, &args.common, cases)?;
    let mut notes = Vec::new();
    let dir = bench.artifact_dir()?;
    quality::run(&mut bench, &gpu, args, &scenes, &dir, &mut notes)?;
    fit::run(&mut bench, &gpu, args, &mut notes)?;
    bench.finish(&notes)?;
    Ok(())
}
