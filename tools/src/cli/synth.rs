//! `lazysolid synth EXEMPLAR --res WxH --offset X,Y --seed S -o out.png`: synthesize a window
//! of the unbounded texture plane from an exemplar on the device, and score it.

use super::components::components;
use super::output::{check_writable, write_png};
use super::resolution::Resolution;
use super::tuning::{Coherence, Energy, Features, Schedule};
use super::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use lazysolid_synth::relief::{relief_map, RELIEF_CODE_MIN};
use lazysolid_synth::{
    analyze_cached, histogram_distance, jitter_or_default, load_plane, passes_or_default,
    period_repetition, unpack, AnalysisParams, Border, DiskCache, EnergyKernel, EnergyReport,
    FittedExemplar, GpuSynthesizer, Region, SynthParams,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What to synthesize and where to write it.
#[derive(Args)]
pub struct SynthArgs {
    /// The exemplar: a name in the assets' exemplars (leather, brick, ...) or a path to a PNG,
    /// JPEG or GIMP pattern (.pat), grey or colour; any size from 16 pixels a side, used as it
    /// is up to 512 and resampled to fit 512 above (the line `exemplar fit:` says which).
    #[arg(value_name = "NAME|PATH")]
    pub exemplar: String,
    /// Output size WxH in pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "256x256")]
    pub res: Resolution,
    /// Absolute position X,Y of the window's first pixel in the unbounded output plane.
    #[arg(long, default_value = "0,0", value_parser = parse_offset, allow_hyphen_values = true)]
    pub offset: (i32, i32),
    /// Seed of the jitter.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// The exemplar does not tile: clamp at its borders instead of wrapping (a resample of an
    /// image over 512 pixels clamps too).
    #[arg(long)]
    pub clamp: bool,
    /// Neither read nor write the on-disk cache of exemplar analyses (kept in
    /// LAZYSOLID_CACHE_DIR, else in the user's cache folder, e.g. ~/.cache/lazysolid).
    #[arg(long)]
    pub no_cache: bool,
    #[command(flatten)]
    pub energy: Energy,
    /// The PNG to write; the coordinate map goes next to it as NAME.coords.png (both checked
    /// before synthesis starts).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the synthesized relief channel as a grey PNG: the exemplar's clamped
    /// feature distance (features dark, the matter farthest from them white) looked up through
    /// the synthesized coordinates, as a store's alpha byte carries it for `relief`.
    #[arg(long, value_name = "PNG")]
    pub relief_out: Option<PathBuf>,
    #[command(flatten)]
    pub schedule: Schedule,
    #[command(flatten)]
    pub coherence: Coherence,
    #[command(flatten)]
    pub features: Features,
}

fn parse_offset(s: &str) -> Result<(i32, i32), String> {
    components(s, " (e.g. -512,1024)", "a whole number").map(|[x, y]| (x, y))
}

/// `out.png` → `out.coords.png`.
fn coords_path(output: &Path) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.coords.png"))
}

/// Runs the command.
pub fn run(args: &SynthArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    ensure!(
        args.output
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png")),
        "-o {}: the output must be a .png file",
        args.output.display()
    );
    check_writable("-o", &args.output)?;
    check_writable("-o", &coords_path(&args.output))?;
    if let Some(path) = &args.relief_out {
        ensure!(
            path.extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("png")),
            "--relief-out {}: the relief channel is written as a .png file",
            path.display()
        );
        check_writable("--relief-out", path)?;
    }
    let exemplar_path = assets::exemplar("EXEMPLAR", &args.exemplar, None)?;
    let border = if args.clamp {
        Border::Clamp
    } else {
        Border::Wrap
    };
    let FittedExemplar { exemplar, fit } = load_plane(&exemplar_path, border)?;
    let cache = if args.no_cache {
        None
    } else {
        Some(DiskCache::user().context("the analysis cache (--no-cache runs without it)")?)
    };
    let start = Instant::now();
    let analysis_params = AnalysisParams {
        k: args.coherence.k,
        spread: args.coherence.spread,
        toroidal: !args.clamp,
        feature_weight: args.features.feature_weight,
        feature_mask: args.features.feature_mask.into(),
    };
    let (analysis, cached) = analyze_cached(&exemplar, &analysis_params, cache.as_ref())?;
    let analysis_s = start.elapsed().as_secs_f64();
    let levels = analysis.levels.len() as u32;
    let params = SynthParams::new(
        levels,
        args.seed,
        &passes_or_default(
            &args.schedule.passes,
            levels,
            exemplar.width.min(exemplar.height),
        ),
        &jitter_or_default(&args.schedule.jitter, levels),
    )?
    .with_period_penalty(args.coherence.period_penalty)?;
    let window = Region {
        origin: [args.offset.0, args.offset.1],
        size: [args.res.width, args.res.height],
    };
    let gpu = global.gpu()?;
    let synth = GpuSynthesizer::new(&gpu, &analysis)?;
    let bar = ProgressBar::new(levels as u64).with_style(
        ProgressStyle::with_template("{msg} [{bar:30}] level {pos}/{len} {elapsed}")
            .expect("valid template"),
    );
    bar.set_message("synthesizing");
    let start = Instant::now();
    let result = synth.synthesize(&analysis, &params, window, false, &mut |_| bar.inc(1))?;
    let synth_s = start.elapsed().as_secs_f64();
    bar.finish_and_clear();

    let (w, h) = (args.res.width, args.res.height);
    let colours = result.colours(&exemplar);
    let window_coords = result.window_coords();
    let repetition = period_repetition(&window_coords, w, h, exemplar.width, exemplar.height);
    let coords: Vec<[u8; 3]> = window_coords
        .iter()
        .map(|&c| {
            let (x, y) = unpack(c);
            [
                (x * 256 / exemplar.width) as u8,
                (y * 256 / exemplar.height) as u8,
                0,
            ]
        })
        .collect();
    write_png(&args.output, w, h, &colours)?;
    let coords_out = coords_path(&args.output);
    write_png(&coords_out, w, h, &coords)?;
    let relief = match &args.relief_out {
        Some(path) => {
            let map = relief_map(&exemplar, !args.clamp, analysis_params.feature_mask);
            let grey: Vec<[u8; 3]> = window_coords
                .iter()
                .map(|&c| {
                    let (x, y) = unpack(c);
                    [map.codes[(y * exemplar.width + x) as usize]; 3]
                })
                .collect();
            write_png(path, w, h, &grey)?;
            Some((path, map.clamp))
        }
        None => None,
    };

    let start = Instant::now();
    let energy = EnergyKernel::new(&gpu)?;
    let minima = energy.minima(&exemplar, &colours, w, h, args.energy.samples)?;
    let report = EnergyReport::from_minima(&minima);
    let energy_s = start.elapsed().as_secs_f64();
    let histogram = histogram_distance(&exemplar.rgb, &colours);
    let figures = lazysolid_synth::quality::ExemplarFigures::new(
        &exemplar.rgb,
        exemplar.width,
        exemplar.height,
    )
    .measure(&colours, w, h);

    println!(
        "exemplar {} ({}x{}, {} levels, k = {})",
        exemplar_path.display(),
        exemplar.width,
        exemplar.height,
        levels,
        args.coherence.k
    );
    println!("exemplar fit: {fit}");
    if analysis_params.feature_weight > 0 {
        let colours: Vec<[f32; 3]> = exemplar.rgb.iter().map(|p| p.map(f32::from)).collect();
        let map = lazysolid_synth::feature::feature_map(
            &colours,
            exemplar.width,
            exemplar.height,
            analysis_params.toroidal,
            analysis_params.feature_weight,
            analysis_params.feature_mask,
        );
        println!(
            "{}",
            map.describe(&exemplar.source, analysis_params.feature_weight)
        );
    }
    println!(
        "window {}x{} at ({}, {}), seed {}, passes {:?}",
        w, h, args.offset.0, args.offset.1, args.seed, params.passes
    );
    println!(
        "analysis (CPU)   {:8.3} s (cache {}{})",
        analysis_s,
        cached.label(),
        cache
            .as_ref()
            .map(|c| format!(", {}", c.dir().display()))
            .unwrap_or_default()
    );
    println!("synthesis (GPU)  {:8.3} s", synth_s);
    println!("energy (GPU)     {:8.3} s", energy_s);
    println!(
        "neighbourhood energy {:.1} per 7x7 neighbourhood ({:.2} per value, {} samples)",
        report.mean, report.per_value, report.samples
    );
    println!("colour histogram distance {histogram:.4}");
    println!(
        "SWD {:.2} ({:.2}x the exemplar's own), blockiness {:.2}",
        figures.swd.mean, figures.swd.ratio, figures.blockiness.ratio
    );
    println!(
        "period repetition {repetition:.3} (share of pixels one exemplar period apart that copy \
         the same exemplar pixel; the plain tiling is 1)"
    );
    println!(
        "layout repetition {:.3} (correlation of the large structures one exemplar period apart; \
         the plain tiling is 1, independent placement about 0)",
        figures.layout
    );
    println!(
        "wrote {} and {}",
        args.output.display(),
        coords_out.display()
    );
    if let Some((path, clamp)) = relief {
        println!(
            "wrote {} (relief channel: feature distance -{clamp}..{clamp} px as codes {RELIEF_CODE_MIN}..255)",
            path.display()
        );
    }
    Ok(())
}
