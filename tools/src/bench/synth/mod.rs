//! `lazysolid bench synth`: the GPU appearance-space synthesis against Embark's
//! `texture-synthesis` crate on the same exemplars and output sizes, timed and scored alike.
//!
//! Rows of every case (one exemplar, one output size; a row's ratio is texture-synthesis min /
//! its min):
//! - `gpu passes (timestamps)`: the device time of the upsample-and-jitter and correction
//!   dispatches of every level, from GPU timestamps (no submission, waiting or read-back);
//! - `synthesize (wall)`: the same call timed on the host: per-level submissions, waits and the
//!   read-back of the finest level, the analysis already on the GPU;
//! - `end-to-end cold (wall)`: the exemplar analysis on the CPU (written to the analysis cache),
//!   kernel creation and upload, synthesis, and the exemplar lookup to colours: from exemplar
//!   pixels to output pixels, as on the first run of an exemplar;
//! - `end-to-end warm (wall)`: the same with the analysis read from the cache, as on every
//!   later run (the bench keeps its cache in a temporary folder, not the user's);
//! - texture-synthesis: session build and run (the crate has no separate analysis step).
//!
//! The exemplar analysis is its own case per exemplar: the papers treat it as a precomputation.

mod baseline;
mod quality;

use super::harness::{time_cpu, Bench, Throughput};
use super::plot::bar_chart;
use super::CommonArgs;
use crate::cli::assets::ExemplarDir;
use crate::cli::resolution::Resolution;
use crate::cli::tuning::{Energy, Schedule};
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use lazysolid_compute::gpu::Gpu;
use lazysolid_synth::quality::ExemplarFigures;
use lazysolid_synth::{
    analysis_key, analyze, analyze_cached, jitter_or_default, load_plane, passes_or_default,
    AnalysisParams, Border, CacheOutcome, DiskCache, EnergyKernel, Exemplar, ExemplarAnalysis,
    GpuSynthesizer, LevelTimes, Region, SynthParams, ANALYSIS_CACHE_KIND, DEFAULT_COARSE_JITTER,
    DEFAULT_FINEST_PASSES, DEFAULT_PASSES,
};
use quality::SeedScores;

/// What to compare.
#[derive(Args)]
pub struct SynthArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Exemplars: names of GIMP patterns (NAME.pat in --exemplar-dir), or paths to PNG, JPEG
    /// or .pat files of any size from 16 pixels a side (resampled above 512, as `synth` does).
    #[arg(
        long,
        value_name = "NAME|PATH",
        value_delimiter = ',',
        default_value = "leather,brick,walnut"
    )]
    pub exemplars: Vec<String>,
    #[command(flatten)]
    pub exemplar_dir: ExemplarDir,
    /// Output sizes, one case each (square: N or NxN).
    #[arg(
        long,
        value_name = "WxH",
        value_delimiter = ',',
        default_value = "256,512"
    )]
    pub res: Vec<Resolution>,
    /// Seed of both synthesizers in the timed runs, and the first of the scored seeds.
    #[arg(long, default_value_t = 3)]
    pub seed: u32,
    /// Seeds each synthesizer's quality is averaged over (--seed, --seed + 1, ...): one seed's
    /// energy moves by up to ±45 % with the layout it draws, so fewer seeds decide little.
    #[arg(long, default_value_t = 8)]
    pub quality_seeds: u32,
    #[command(flatten)]
    pub energy: Energy,
    /// CPU threads of texture-synthesis and of the exemplar analysis.
    #[arg(long, default_value_t = 2)]
    pub cpu_threads: usize,
    /// Only the first exemplar at the first size.
    #[arg(long)]
    pub quick: bool,
    #[command(flatten)]
    pub schedule: Schedule,
}

/// Smallest and largest output side: the 7×7 energy needs 7 pixels, and the baseline's time
/// grows too fast beyond 2048.
const SIZE_RANGE: std::ops::RangeInclusive<u32> = 7..=2048;

const GPU_PASSES: &str = "lazysolid gpu passes (timestamps)";
const GPU_WALL: &str = "lazysolid synthesize (wall)";
const END_TO_END_COLD: &str = "lazysolid end-to-end cold (wall)";
const END_TO_END_WARM: &str = "lazysolid end-to-end warm (wall)";

/// Project targets (docs/synthesis.md).
const TARGET_SPEEDUP: f64 = 20.0;
const TARGET_WARM_SIZE: u32 = 256;
const TARGET_REPETITION: f64 = 0.35;
const TARGET_ENERGY_MARGIN: f64 = 1.05;
const TARGET_512_FROM_64_MS: f64 = 500.0;

/// Most scored seeds per case (each costs one more run of texture-synthesis).
const MAX_QUALITY_SEEDS: u32 = 16;

/// One exemplar and output size, measured.
struct CaseResult {
    case: String,
    exemplar_side: u32,
    size: u32,
    passes_ms: f64,
    wall_ms: f64,
    cold_ms: f64,
    warm_ms: f64,
    baseline_ms: f64,
    levels: Vec<LevelTimes>,
    ours: SeedScores,
    theirs: SeedScores,
}

fn display_name(path: &std::path::Path) -> String {
    path.file_stem()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned()
}

/// What one end-to-end run needs: from exemplar pixels to output colours.
struct EndToEnd<'a> {
    gpu: &'a Gpu,
    pool: &'a rayon::ThreadPool,
    cache: &'a DiskCache,
    exemplar: &'a Exemplar,
    analysis: &'a AnalysisParams,
    params: &'a SynthParams,
}

impl EndToEnd<'_> {
    /// Analysis through the cache, kernels and upload, synthesis of `window`, colours; timed
    /// on the host. Fails unless the cache did `expected` (a miss when cold, a hit when warm),
    /// so that the rows measure what they are named for.
    fn run(&self, window: Region, expected: &CacheOutcome) -> anyhow::Result<(Vec<[u8; 3]>, f64)> {
        let (result, ms) = time_cpu(|| -> anyhow::Result<_> {
            let (a, outcome) = self
                .pool
                .install(|| analyze_cached(self.exemplar, self.analysis, Some(self.cache)))?;
            let s = GpuSynthesizer::new(self.gpu, &a)?;
            let colours = s
                .synthesize(&a, self.params, window, false, &mut |_| {})?
                .colours(self.exemplar);
            Ok((colours, outcome))
        });
        let (colours, outcome) = result?;
        ensure!(
            &outcome == expected,
            "analysis cache: expected {expected:?}, got {outcome:?}"
        );
        Ok((colours, ms))
    }
}

/// Runs the suite.
pub fn run(args: &SynthArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    ensure!(!args.exemplars.is_empty(), "--exemplars names no exemplar");
    ensure!(!args.res.is_empty(), "--res names no size");
    let all_sizes = args
        .res
        .iter()
        .map(|r| {
            r.check("--res", SIZE_RANGE)?;
            r.side("--res", "each output")
        })
        .collect::<anyhow::Result<Vec<u32>>>()?;
    ensure!(args.cpu_threads >= 1, "--cpu-threads must be at least 1");
    ensure!(
        (1..=MAX_QUALITY_SEEDS).contains(&args.quality_seeds),
        "--quality-seeds {} is out of range (1..={MAX_QUALITY_SEEDS})",
        args.quality_seeds
    );
    let (names, sizes) = if args.quick {
        (&args.exemplars[..1], &all_sizes[..1])
    } else {
        (&args.exemplars[..], &all_sizes[..])
    };
    let exemplars = names
        .iter()
        .map(|n| {
            let path = assets::exemplar("--exemplars", n, args.exemplar_dir.path.as_deref())?;
            let fitted = load_plane(&path, Border::Wrap).with_context(|| {
                format!(
                    "loading exemplar {} (scripts/fetch-assets.sh fetches the GIMP patterns)",
                    path.display()
                )
            })?;
            // As `lazysolid synth`: any size, resampled above 512, and said so.
            if !fitted.fit.is_native() {
                println!("exemplar fit: {}", fitted.fit);
            }
            Ok((display_name(&path), fitted.exemplar))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let gpu = global.gpu()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.cpu_threads)
        .build()?;
    let threads = args.cpu_threads;
    let cases = exemplars.len() as u64 * (1 + 5 * sizes.len() as u64);
    let mut bench = Bench::new("bench-synth", &gpu, &args.common, cases)?;
    let analysis_params = AnalysisParams::default();
    let cache_dir = tempfile::Builder::new()
        .prefix("lazysolid-bench-cache-")
        .tempdir()
        .context("creating a temporary analysis cache folder")?;
    let cache = DiskCache::new(cache_dir.path());
    let energy = EnergyKernel::new(&gpu)?;
    let baseline_name = format!("texture-synthesis 0.8.2 ({threads} threads)");
    let mut results = Vec::new();
    let mut figures = Vec::new();

    for (name, exemplar) in &exemplars {
        let tag = format!("{name} {}x{}", exemplar.width, exemplar.height);
        let mut analysis: Option<ExemplarAnalysis> = None;
        bench.case(
            &format!("{tag} analysis"),
            exemplar.rgb.len() as u64,
            &format!("lazysolid cpu analysis ({threads} thr)"),
            Throughput::Elements,
            None,
            || {
                let (a, ms) = time_cpu(|| pool.install(|| analyze(exemplar, &analysis_params)));
                analysis = Some(a?);
                Ok(ms)
            },
        )?;
        let analysis = analysis.expect("analysed at least once");
        let levels = analysis.levels.len() as u32;
        let passes = passes_or_default(
            &args.schedule.passes,
            levels,
            exemplar.width.min(exemplar.height),
        );
        let jitter = jitter_or_default(&args.schedule.jitter, levels);
        let params = SynthParams::new(levels, args.seed, &passes, &jitter)?;
        let synth = GpuSynthesizer::new(&gpu, &analysis)?;
        let key = analysis_key(exemplar, &analysis_params);
        let end_to_end = EndToEnd {
            gpu: &gpu,
            pool: &pool,
            cache: &cache,
            exemplar,
            analysis: &analysis_params,
            params: &params,
        };

        for &size in sizes {
            let case = format!("{tag} -> {size}x{size}");
            let pixels = size as u64 * size as u64;
            let window = Region {
                origin: [0, 0],
                size: [size, size],
            };
            let mut level_times = Vec::new();
            let passes_ms = bench.case(
                &case,
                pixels,
                GPU_PASSES,
                Throughput::Elements,
                Some(&baseline_name),
                || {
                    let (_, times) =
                        synth.synthesize_timed(&analysis, &params, window, false, &mut |_| {})?;
                    let ms = times.iter().map(|t| t.upsample_ms + t.correct_ms).sum();
                    level_times = times;
                    Ok(ms)
                },
            )?;
            let mut ours = Vec::new();
            let mut ours_coords = Vec::new();
            let wall_ms = bench.case(
                &case,
                pixels,
                GPU_WALL,
                Throughput::Elements,
                Some(&baseline_name),
                || {
                    let (s, ms) = time_cpu(|| {
                        synth.synthesize(&analysis, &params, window, false, &mut |_| {})
                    });
                    let s = s?;
                    ours = s.colours(exemplar);
                    ours_coords = s.window_coords();
                    Ok(ms)
                },
            )?;
            let cold_ms = bench.case(
                &case,
                pixels,
                END_TO_END_COLD,
                Throughput::Elements,
                Some(&baseline_name),
                || {
                    cache.remove(ANALYSIS_CACHE_KIND, &key)?;
                    let (colours, ms) = end_to_end.run(window, &CacheOutcome::Miss)?;
                    ensure!(colours == ours, "{case}: cold end-to-end output differs");
                    Ok(ms)
                },
            )?;
            let warm_ms = bench.case(
                &case,
                pixels,
                END_TO_END_WARM,
                Throughput::Elements,
                Some(&baseline_name),
                || {
                    let (colours, ms) = end_to_end.run(window, &CacheOutcome::Hit)?;
                    ensure!(colours == ours, "{case}: warm end-to-end output differs");
                    Ok(ms)
                },
            )?;
            let mut theirs = None;
            let baseline_ms = bench.case(
                &case,
                pixels,
                &baseline_name,
                Throughput::Elements,
                None,
                || {
                    let (out, ms) = time_cpu(|| {
                        baseline::synthesize(exemplar, size, args.seed as u64, threads)
                    });
                    theirs = Some(out?);
                    Ok(ms)
                },
            )?;
            let theirs = baseline::output(
                theirs.expect("texture-synthesis ran at least once"),
                exemplar,
                size,
            )?;
            let calibration = ExemplarFigures::new(&exemplar.rgb, exemplar.width, exemplar.height);
            let score = |image: &[[u8; 3]], coords: &[u32]| {
                quality::measure(
                    &energy,
                    &calibration,
                    exemplar,
                    image,
                    coords,
                    size,
                    args.energy.samples,
                )
            };
            let mut ours_q = SeedScores {
                per_seed: vec![score(&ours, &ours_coords)?],
            };
            let mut theirs_q = SeedScores {
                per_seed: vec![score(&theirs.rgb, &theirs.coords)?],
            };
            for extra in 1..args.quality_seeds {
                let seed = args.seed.wrapping_add(extra);
                bench.status(format!("{case} — scoring seed {seed} of both"));
                let p = SynthParams::new(levels, seed, &passes, &jitter)?;
                let s = synth.synthesize(&analysis, &p, window, false, &mut |_| {})?;
                ours_q
                    .per_seed
                    .push(score(&s.colours(exemplar), &s.window_coords())?);
                let generated = baseline::synthesize(exemplar, size, seed as u64, threads)?;
                let t = baseline::output(generated, exemplar, size)?;
                theirs_q.per_seed.push(score(&t.rgb, &t.coords)?);
            }
            figures.push((
                format!("{name}-{size}-lazysolid-vs-texture-synthesis.png"),
                ours,
                theirs.rgb,
                size,
            ));
            results.push(CaseResult {
                case,
                exemplar_side: exemplar.width.max(exemplar.height),
                size,
                passes_ms,
                wall_ms,
                cold_ms,
                warm_ms,
                baseline_ms,
                levels: level_times,
                ours: ours_q,
                theirs: theirs_q,
            });
        }
    }

    let dir = bench.artifact_dir()?;
    for (file, ours, theirs, size) in &figures {
        quality::side_by_side(&dir.join(file), ours, theirs, *size)?;
    }
    bar_chart(
        &dir.join("synth-times.png"),
        "synthesis time (min): lazysolid (lavapipe) vs texture-synthesis (CPU)",
        "exemplar -> output",
        "ms",
        &results.iter().map(|r| r.case.clone()).collect::<Vec<_>>(),
        &[
            (
                "lazysolid gpu passes".to_string(),
                results.iter().map(|r| r.passes_ms).collect(),
            ),
            (
                "lazysolid end-to-end cold".to_string(),
                results.iter().map(|r| r.cold_ms).collect(),
            ),
            (
                "lazysolid end-to-end warm".to_string(),
                results.iter().map(|r| r.warm_ms).collect(),
            ),
            (
                baseline_name.clone(),
                results.iter().map(|r| r.baseline_ms).collect(),
            ),
        ],
        true,
    )?;

    let mut notes = vec![
        (
            "energy samples (max)".to_string(),
            args.energy.samples as f64,
        ),
        ("seed".to_string(), args.seed as f64),
        ("quality seeds".to_string(), args.quality_seeds as f64),
        (
            "jitter (coarsest level)".to_string(),
            args.schedule
                .jitter
                .first()
                .copied()
                .unwrap_or(DEFAULT_COARSE_JITTER[0]) as f64,
        ),
        (
            "passes (finest level)".to_string(),
            args.schedule
                .passes
                .last()
                .copied()
                .unwrap_or(DEFAULT_FINEST_PASSES) as f64,
        ),
        (
            "passes (other levels)".to_string(),
            args.schedule
                .passes
                .first()
                .copied()
                .unwrap_or(DEFAULT_PASSES) as f64,
        ),
        ("baseline threads".to_string(), threads as f64),
    ];
    for r in &results {
        let c = &r.case;
        notes.extend([
            (format!("{c}: lazysolid energy"), r.ours.energy()),
            (format!("{c}: texture-synthesis energy"), r.theirs.energy()),
            (
                format!("{c}: lazysolid energy min"),
                r.ours.energy_range().0,
            ),
            (
                format!("{c}: lazysolid energy max"),
                r.ours.energy_range().1,
            ),
            (
                format!("{c}: texture-synthesis energy min"),
                r.theirs.energy_range().0,
            ),
            (
                format!("{c}: texture-synthesis energy max"),
                r.theirs.energy_range().1,
            ),
            (format!("{c}: lazysolid SWD ratio"), r.ours.swd_ratio()),
            (
                format!("{c}: texture-synthesis SWD ratio"),
                r.theirs.swd_ratio(),
            ),
            (format!("{c}: lazysolid layout repetition"), r.ours.layout()),
            (
                format!("{c}: texture-synthesis layout repetition"),
                r.theirs.layout(),
            ),
            (format!("{c}: lazysolid blockiness"), r.ours.blockiness()),
            (
                format!("{c}: texture-synthesis blockiness"),
                r.theirs.blockiness(),
            ),
            (
                format!("{c}: lazysolid histogram distance"),
                r.ours.histogram(),
            ),
            (
                format!("{c}: texture-synthesis histogram distance"),
                r.theirs.histogram(),
            ),
            (
                format!("{c}: lazysolid period repetition"),
                r.ours.repetition(),
            ),
            (
                format!("{c}: texture-synthesis period repetition"),
                r.theirs.repetition(),
            ),
            (format!("{c}: energy samples"), r.ours.samples() as f64),
            (
                format!("{c}: gpu upsample ms"),
                r.levels.iter().map(|t| t.upsample_ms).sum(),
            ),
            (
                format!("{c}: gpu correction ms"),
                r.levels.iter().map(|t| t.correct_ms).sum(),
            ),
            (
                format!("{c}: gpu finest level ms"),
                r.levels
                    .last()
                    .map_or(0.0, |t| t.upsample_ms + t.correct_ms),
            ),
        ]);
    }
    bench.finish(&notes)?;
    println!();
    println!("baseline: {}", baseline::settings(threads));
    print_quality(&results, args.quality_seeds);
    print_profile(&results);
    print_targets(&results);
    Ok(())
}

fn print_quality(results: &[CaseResult], seeds: u32) {
    println!();
    println!(
        "quality against the exemplar, mean of {seeds} seed(s) (7x7 neighbourhood energy: mean \
         per neighbourhood, per value and the single-seed range; colour-histogram distance; \
         period repetition: share of pixels one exemplar period apart copying exemplar pixels at most 4 apart; \
         layout: correlation of the large structures one exemplar period apart, 1 for a tiling)"
    );
    println!(
        "{:<28} {:>8} {:>34} {:>34} {:>10} {:>11} {:>9} {:>10} {:>11} {:>13} {:>9} {:>11} {:>10} {:>12}",
        "case",
        "samples",
        "energy lazysolid",
        "energy tex-synth",
        "hist ours",
        "hist theirs",
        "rep ours",
        "rep theirs",
        "layout ours",
        "layout theirs",
        "SWDr ours",
        "SWDr theirs",
        "block ours",
        "block theirs"
    );
    let cell = |q: &SeedScores| {
        let (lo, hi) = q.energy_range();
        format!(
            "{:.1} ({:.2}) [{lo:.0}..{hi:.0}]",
            q.energy(),
            q.energy_per_value()
        )
    };
    for r in results {
        println!(
            "{:<28} {:>8} {:>34} {:>34} {:>10.4} {:>11.4} {:>9.3} {:>10.3} {:>11.3} {:>13.3} {:>9.2} {:>11.2} {:>10.2} {:>12.2}",
            r.case,
            r.ours.samples(),
            cell(&r.ours),
            cell(&r.theirs),
            r.ours.histogram(),
            r.theirs.histogram(),
            r.ours.repetition(),
            r.theirs.repetition(),
            r.ours.layout(),
            r.theirs.layout(),
            r.ours.swd_ratio(),
            r.theirs.swd_ratio(),
            r.ours.blockiness(),
            r.theirs.blockiness()
        );
    }
}

fn print_profile(results: &[CaseResult]) {
    println!();
    println!("gpu profile of the last timed run (timestamps, ms)");
    for r in results {
        let up: f64 = r.levels.iter().map(|t| t.upsample_ms).sum();
        let corr: f64 = r.levels.iter().map(|t| t.correct_ms).sum();
        let per_level = r
            .levels
            .iter()
            .map(|t| {
                format!(
                    "L{} {}px {:.1}",
                    t.level,
                    t.pixels,
                    t.upsample_ms + t.correct_ms
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        println!(
            "{}: upsample+jitter {up:.2}, correction {corr:.2} ({:.0}%); per level: {per_level}",
            r.case,
            100.0 * corr / (up + corr).max(f64::MIN_POSITIVE)
        );
    }
}

fn print_targets(results: &[CaseResult]) {
    println!();
    for r in results {
        let speedup = r.baseline_ms / r.passes_ms;
        let wall_speedup = r.baseline_ms / r.wall_ms;
        let (ours, theirs) = (r.ours.energy(), r.theirs.energy());
        let repetition = r.ours.repetition();
        let met = speedup >= TARGET_SPEEDUP
            && repetition <= TARGET_REPETITION
            && ours <= TARGET_ENERGY_MARGIN * theirs;
        println!(
            "target {}: >= {TARGET_SPEEDUP}x faster, repetition <= {TARGET_REPETITION} and energy \
             within {:.0}% of texture-synthesis's or lower: {} (gpu passes {speedup:.1}x, \
             synthesize wall {wall_speedup:.1}x, end-to-end cold {:.1}x, warm {:.1}x; \
             repetition {repetition:.3}; mean energy {ours:.1} vs {theirs:.1}, {:+.1}%)",
            r.case,
            100.0 * (TARGET_ENERGY_MARGIN - 1.0),
            if met { "met" } else { "missed" },
            r.baseline_ms / r.cold_ms,
            r.baseline_ms / r.warm_ms,
            100.0 * (ours / theirs - 1.0)
        );
    }
    for r in results.iter().filter(|r| r.size == TARGET_WARM_SIZE) {
        let warm = r.baseline_ms / r.warm_ms;
        println!(
            "target {}: warm end-to-end >= {TARGET_SPEEDUP}x faster: {} ({warm:.1}x, {:.1} ms \
             against {:.1} ms; cold {:.1} ms)",
            r.case,
            if warm >= TARGET_SPEEDUP {
                "met"
            } else {
                "missed"
            },
            r.warm_ms,
            r.baseline_ms,
            r.cold_ms
        );
    }
    for r in results
        .iter()
        .filter(|r| r.exemplar_side == 64 && r.size == 512)
    {
        println!(
            "target {}: under {TARGET_512_FROM_64_MS} ms: gpu passes {:.1} ms ({}), synthesize wall {:.1} ms ({})",
            r.case,
            r.passes_ms,
            if r.passes_ms < TARGET_512_FROM_64_MS { "met" } else { "missed" },
            r.wall_ms,
            if r.wall_ms < TARGET_512_FROM_64_MS { "met" } else { "missed" },
        );
    }
}
