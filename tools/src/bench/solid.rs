//! `lazysolid bench solid`: solid synthesis timed and scored per axis against its exemplars,
//! beside the 2D synthesizer's output of the same exemplar and two ablations.
//!
//! Every exemplar is fitted to the side measured by `--fit` (`lazysolid solid`'s rule, so a
//! 144² or 100² pattern is measured at 128), and the handling is printed and recorded in
//! `quality.json`.
//!
//! Timed rows (wall time on the host): the candidate precompute per exemplar side
//! (`--candidate-sides`, default 64 and 128) and the synthesis of a cube per `--voxel-res`
//! (default 64 and 128: the GPU synthesis alone, the candidates read from the cache), and per
//! case the whole preparation and cube of the recipe — CPU analysis, candidates, kernels, synthesis, colours,
//! slab — with the candidate cache cold (entry removed before each run: the precompute is
//! paid; first size only) and warm (read back, as on every later run of an exemplar). The
//! cache is a temporary folder, not the user's. Quality, from one run
//! at the first size: for each axis the mid slice perpendicular to it against that axis's
//! exemplar — the multi-scale sliced Wasserstein distance and its ratio to the exemplar's own
//! variability, blockiness, neighbourhood energy, colour-histogram distance and period
//! repetition (`synth::quality`), the SWD ratio and blockiness also averaged over eight slices
//! per axis (`SWD8`: one slice's ratio moves by up to ±0.3 between slices and seeds; with
//! `--solid-seeds N` the `solid` row pools the eight slices of N seeds, since one seed still
//! moves the eight-slice mean by up to 0.48) — and, for
//! the solid variants, how consistent the triples are
//! (`TripleConsistency`), for
//! - `solid`: the defaults;
//! - `own role`, `mean colour`: the defaults' triples, each axis's slice coloured by its own
//!   role's exemplar alone (a diagnostic, not a volume) or by the mean of the three instead of
//!   the median;
//! - `no balance`: candidates without the usage balance (`balance.rs`), which shows how much
//!   of the exemplar's contrast the balance keeps;
//! - `balance finest`: the usage balance at the finest level only (`--balance-levels 1`),
//!   which is where slate's slices lose their excess contrast at 2–4 pixels;
//! - `no feature`: the appearance space of colour alone, without the feature-distance
//!   channel (`synth/feature.rs`), which shows what the channel adds;
//! - `otsu mask`: the features found by Otsu's split always, which shows what the rule gains
//!   by taking the minimum-error split where Otsu's takes part of the body (`synth/feature.rs`);
//! - `as given`: every role sees its image as given, where the orientation rule mirrored one
//!   (`solid/orientation.rs`), scored against the images as given, which shows what the
//!   mirroring gains;
//! - `keep current`: the correction's current triple competes even when it is none of the
//!   gathered candidates, which brings back the axis-aligned blocks that leaving it out
//!   removes (`docs/solid.md`, "Correction");
//! - `crossbar only`: candidates without the coherence filter (each pixel's 12 smallest
//!   crossbar errors);
//! - `extruded`: every voxel copies `E_z` at its (x, y), i.e. `E_z` extruded along z;
//! - `2d synth`: the 2D synthesizer's output of the axis's exemplar at the same side (its
//!   `SWD8` the mean over eight seeds, as the solid's over eight slices).

use super::harness::{time_cpu, Bench, Throughput};
use super::CommonArgs;
use crate::cli::assets;
use crate::cli::assets::ExemplarDir;
use crate::cli::candidate_builder::Candidates;
use crate::cli::fit_mode::Fit;
use crate::cli::output::write_png;
use crate::cli::tuning::{Energy, OrientationRule, Schedule, SolidOrder};
use crate::cli::GlobalArgs;
use anyhow::{ensure, Context};
use clap::Args;
use lazysolid_compute::atomic_file::write_bytes_atomically;
use lazysolid_compute::gpu::Gpu;
use lazysolid_synth::cache::{CacheOutcome, DiskCache};
use lazysolid_synth::feature::FeatureMask;
use lazysolid_synth::solid::{
    axis_quality, candidates_key, oblique, role_scorers, slice, slice_ratios, AxisQuality,
    CandidateBuilder, CandidateParams, ImageScorer, LevelTriples, Mirroring, Orientation,
    PreparedSolid, SliceRatios, SolidCube, SolidExemplars, SolidRecipe, SolidSchedule,
    SolidSources, SolidSynthesis, TripleConsistency, VolumeBox, CANDIDATES_CACHE_KIND,
    DEFAULT_SOLID_PARALLEL_LEVELS, QUALITY_SLICES, ROLE_NAMES,
};
use lazysolid_synth::{
    analyze, default_passes_for, default_plane_jitter, pack, period_repetition, unpack,
    AnalysisParams, EnergyKernel, Exemplar, GpuSynthesizer, Region, SynthParams,
};
use serde::Serialize;

const CANDIDATES_GPU: &str = "lazysolid gpu kernels (wall)";
const CANDIDATES_HOST: &str = "lazysolid host, pruned (wall)";
const END_TO_END_COLD: &str = "lazysolid end-to-end cold (wall)";
const END_TO_END_WARM: &str = "lazysolid end-to-end warm (wall)";

/// What to measure.
#[derive(Args)]
pub struct SolidArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Exemplars playing all three roles: GIMP pattern names in --exemplar-dir (NAME.pat) or
    /// paths; each is fitted to the side measured by --fit, as `lazysolid solid` fits it, so
    /// that the bench measures the exemplar a user gets.
    #[arg(
        long,
        value_name = "NAME|PATH",
        value_delimiter = ',',
        default_value = "brick,terra,walnut,pink_marble"
    )]
    pub exemplars: Vec<String>,
    /// Three exemplars playing E_x, E_y, E_z of one more case (empty: none).
    #[arg(long, value_delimiter = ',', default_value = "terra,brick,walnut")]
    pub three: Vec<String>,
    #[command(flatten)]
    pub exemplar_dir: ExemplarDir,
    /// Exemplar sides whose candidate precompute is timed.
    #[arg(long, value_delimiter = ',', default_value = "64,128")]
    pub candidate_sides: Vec<u32>,
    /// Where the candidates are computed, as `lazysolid solid --candidates`, here a list of the
    /// builders timed at each candidate side (side by side, and checked equal when both run);
    /// `host` alone keeps a large side within minutes on a CPU device, where the kernels'
    /// brute force takes about five minutes at 128². `auto` is refused: a timing names its
    /// builder.
    #[arg(long, value_delimiter = ',', default_value = "gpu,host")]
    pub candidates: Vec<Candidates>,
    /// Exemplar side of the synthesis and quality cases.
    #[arg(long, default_value_t = 64)]
    pub side: u32,
    /// How each exemplar is fitted to the side measured: auto cuts the centre square when
    /// that loses at most a quarter of the side and resamples otherwise, as `lazysolid solid`.
    #[arg(long, value_enum, default_value_t = Fit::Auto)]
    pub fit: Fit,
    /// Cube sides whose synthesis is timed, in voxels; the first is scored.
    #[arg(
        long,
        value_name = "N",
        value_delimiter = ',',
        default_value = "64,128"
    )]
    pub voxel_res: Vec<u32>,
    /// Seed of the jitter.
    #[arg(long, default_value_t = 3)]
    pub seed: u32,
    /// Seeds of the scored solid (seed, seed + 1, …) whose slices the `solid` row's
    /// eight-slice figures pool (1 to 8): a change of seed moves a per-axis eight-slice SWD
    /// ratio by up to 0.48 (docs/solid.md, "Twelve exemplars on three seeds of the solid"), so
    /// a verdict within that of a limit needs several. The mid-slice figures and the other
    /// rows stay the first seed's.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub solid_seeds: u32,
    #[command(flatten)]
    pub energy: Energy,
    /// Only the first exemplar, the first candidate side and the first size.
    #[arg(long)]
    pub quick: bool,
    /// Score the default synthesis, the colour rules and the 2D synthesis only, without the
    /// seven ablation syntheses (keep current, crossbar only, no balance, the balance at the
    /// finest level only, no feature, Otsu's mask, the finest level's other correction
    /// order): a
    /// table of many exemplars at 128³ in minutes instead of an hour.
    #[arg(long)]
    pub no_ablations: bool,
    #[command(flatten)]
    pub schedule: Schedule,
    #[command(flatten)]
    pub order: SolidOrder,
    #[command(flatten)]
    pub orientation: OrientationRule,
}

/// One quality row: a variant of one case, per axis.
#[derive(Serialize)]
struct QualityRow {
    case: String,
    /// How each exemplar of the case was fitted to the side (`ExemplarFit`'s line).
    exemplars: Vec<String>,
    variant: String,
    axes: [AxisQuality; 3],
    /// The solid variants' triple consistency.
    consistency: Option<TripleConsistency>,
}

/// The recipe of a case (one name for all roles, or three joined by `+`) with its exemplars
/// fitted to `side`² by `--fit` (the rule of `lazysolid solid`) and oriented by
/// `--orientation`: the defaults otherwise, with the suite's seed and schedule.
fn recipe_of(args: &SolidArgs, case: &str, side: u32) -> anyhow::Result<SolidRecipe> {
    let path =
        |name: &str| assets::exemplar("--exemplars", name, args.exemplar_dir.path.as_deref());
    let names: Vec<&str> = case.split('+').collect();
    let roles = if names.len() == 1 {
        [None, None, None]
    } else {
        ensure!(
            names.len() == 3,
            "{case}: a case is one exemplar or three joined by +"
        );
        [
            Some(path(names[0])?),
            Some(path(names[1])?),
            Some(path(names[2])?),
        ]
    };
    Ok(SolidRecipe {
        roles,
        fit: args.fit.into(),
        exemplar_side: Some(side),
        orientation: args.orientation.rule.into(),
        schedule: args.schedule.solid(&args.order),
        seed: args.seed,
        ..SolidRecipe::new(path(names[0])?)
    })
}

/// Loads `recipe`'s exemplars, naming the case on failure.
fn load(recipe: &SolidRecipe, case: &str) -> anyhow::Result<SolidSources> {
    recipe
        .load()
        .with_context(|| format!("loading the exemplars of {case}"))
}

/// `sources` prepared through `cache` and an `n`³ cube at the origin synthesized from them:
/// the whole work of one end-to-end run.
fn cube(
    gpu: &Gpu,
    sources: &SolidSources,
    n: u32,
    cache: Option<&DiskCache>,
) -> anyhow::Result<(PreparedSolid, SolidCube)> {
    let prepared = sources.prepare(gpu, cache, &mut |_, _| {})?;
    let window = VolumeBox {
        origin: [0; 3],
        size: [n; 3],
    };
    let cube = prepared.cube(gpu, window, &mut |_| {})?;
    Ok((prepared, cube))
}

/// The `extruded` ablation: `E_z` at (x, y) everywhere along z, with the triples that say so.
fn extruded(exemplars: &SolidExemplars, n: u32) -> (SolidSynthesis, Vec<[u8; 3]>) {
    let m = exemplars.side();
    let window = VolumeBox {
        origin: [0; 3],
        size: [n; 3],
    };
    let triples: Vec<[u32; 3]> = (0..window.voxels())
        .map(|i| {
            let p = window.position(i).map(|v| v as u32 % m);
            [pack(p[1], 0), pack(p[0], 0), pack(p[0], p[1])]
        })
        .collect();
    let colours = triples
        .iter()
        .map(|t| exemplars.role(2).at(t[2] & 0xffff, t[2] >> 16))
        .collect();
    let synthesis = SolidSynthesis {
        window,
        levels: vec![LevelTriples {
            region: window,
            triples,
        }],
    };
    (synthesis, colours)
}

/// The 2D synthesizer's `n`² output of each role's exemplar, scored like a slice.
fn synth_2d(
    gpu: &Gpu,
    energy: &EnergyKernel,
    scorers: &[ImageScorer; 3],
    exemplars: &SolidExemplars,
    n: u32,
    seed: u32,
    samples: usize,
) -> anyhow::Result<([AxisQuality; 3], Vec<[u8; 3]>)> {
    let mut out: Vec<AxisQuality> = Vec::new();
    let mut image = Vec::new();
    for (r, scorer) in scorers.iter().enumerate() {
        // A role whose image an earlier role plays has that role's 2D figures (the same
        // synthesis, scored against the same exemplar).
        let image_index = exemplars.role_image[r];
        if let Some(earlier) = (0..r).find(|&o| exemplars.role_image[o] == image_index) {
            out.push(out[earlier]);
            continue;
        }
        let e = exemplars.role(r);
        let a = analyze(e, &AnalysisParams::default())?;
        let levels = a.levels.len() as u32;
        let synthesizer = GpuSynthesizer::new(gpu, &a)?;
        // One image per seed, the first scored in full; the others average the SWD ratio and
        // blockiness as the solid's eight slices do (one image is as noisy as one slice).
        let mut first = None;
        let mut figures = Vec::new();
        for k in 0..QUALITY_SLICES {
            let params = SynthParams::new(
                levels,
                seed.wrapping_add(k),
                &default_passes_for(levels, e.width.min(e.height)),
                &default_plane_jitter(levels),
            )?;
            let s = synthesizer.synthesize(
                &a,
                &params,
                Region {
                    origin: [0, 0],
                    size: [n, n],
                },
                false,
                &mut |_| {},
            )?;
            let rgb = s.colours(e);
            if first.is_none() {
                let repetition = period_repetition(&s.window_coords(), n, n, e.width, e.height);
                let q = scorer.score(energy, e, &rgb, n, n, repetition, samples)?;
                figures.push(q.own_ratios());
                first = Some(q);
                if r == 0 {
                    image = rgb;
                }
            } else {
                figures.push(scorer.ratios(&rgb, n, n));
            }
        }
        let mut q = first.expect("at least one seed");
        q.set_means(&figures);
        out.push(q);
    }
    Ok((out.try_into().expect("three roles"), image))
}

/// Exemplar, its two disjoint halves (what the SWD unit compares: the material's own
/// variability, drawn apart by a 4-pixel gap), 2D synthesis, the three mid slices of a cube
/// and its oblique slice side by side (8-pixel gaps).
fn figure(
    exemplar: &Exemplar,
    two_d: &[[u8; 3]],
    synthesis: &SolidSynthesis,
    colours: &[[u8; 3]],
) -> (u32, u32, Vec<[u8; 3]>) {
    let n = synthesis.window.size[0];
    let gap = 8;
    let (ew, eh) = (exemplar.width, exemplar.height);
    let mut panels: Vec<(u32, u32, Vec<[u8; 3]>)> = vec![(ew, eh, exemplar.rgb.clone())];
    // The halves as `SwdCalibration` splits them (across the longer side), side by side.
    let halves = if ew >= eh {
        let half = ew / 2;
        let w = 2 * half + 4;
        let mut rgb = vec![[255u8; 3]; (w * eh) as usize];
        for y in 0..eh {
            for x in 0..2 * half {
                let to = if x < half { x } else { x + 4 };
                rgb[(y * w + to) as usize] = exemplar.rgb[(y * ew + x) as usize];
            }
        }
        (w, eh, rgb)
    } else {
        let half = eh / 2;
        let h = 2 * half + 4;
        let mut rgb = vec![[255u8; 3]; (ew * h) as usize];
        for y in 0..2 * half {
            let to = if y < half { y } else { y + 4 };
            for x in 0..ew {
                rgb[(to * ew + x) as usize] = exemplar.rgb[(y * ew + x) as usize];
            }
        }
        (ew, h, rgb)
    };
    panels.push(halves);
    panels.push((n, n, two_d.to_vec()));
    for axis in 0..3 {
        panels.push((n, n, slice(synthesis, colours, axis, n / 2).0));
    }
    panels.push((n, n, oblique(colours, n as usize)));
    let width: u32 = panels.iter().map(|p| p.0).sum::<u32>() + gap * (panels.len() as u32 - 1);
    let height = panels.iter().map(|p| p.1).max().unwrap_or(0);
    let mut rgb = vec![[255u8; 3]; (width * height) as usize];
    let mut x0 = 0;
    for (w, h, pixels) in panels {
        for y in 0..h {
            for x in 0..w {
                rgb[(y * width + x0 + x) as usize] = pixels[(y * w + x) as usize];
            }
        }
        x0 += w + gap;
    }
    (width, height, rgb)
}

/// Runs the suite.
pub fn run(args: &SolidArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    ensure!(!args.exemplars.is_empty(), "--exemplars names no exemplar");
    ensure!(!args.voxel_res.is_empty(), "--voxel-res names no cube side");
    ensure!(
        !args.candidates.contains(&Candidates::Auto),
        "--candidates auto: bench solid times named builders; list host, gpu or both"
    );
    // `--three ""` names none.
    let three: Vec<&String> = args.three.iter().filter(|n| !n.is_empty()).collect();
    ensure!(
        three.is_empty() || three.len() == 3,
        "--three names {} exemplars; give three (E_x, E_y, E_z) or none",
        three.len()
    );
    let mut cases: Vec<String> = args.exemplars.clone();
    if !three.is_empty() {
        cases.push(
            three
                .iter()
                .map(|n| n.as_str())
                .collect::<Vec<_>>()
                .join("+"),
        );
    }
    let (cases, candidate_sides, sizes) = if args.quick {
        (
            &cases[..1],
            &args.candidate_sides[..1],
            &args.voxel_res[..1],
        )
    } else {
        (&cases[..], &args.candidate_sides[..], &args.voxel_res[..])
    };
    let gpu = global.gpu()?;
    let energy = EnergyKernel::new(&gpu)?;
    let total = cases.len() as u64 * (candidate_sides.len() + 2 * sizes.len() + 1) as u64;
    let mut bench = Bench::new("bench-solid", &gpu, &args.common, total)?;
    let dir = bench.artifact_dir()?;
    // The candidate cache of the synthesis rows: a temporary folder, not the user's.
    let cache_dir = tempfile::Builder::new()
        .prefix("lazysolid-bench-cache-")
        .tempdir()
        .context("creating a temporary candidate cache folder")?;
    let cache = DiskCache::new(cache_dir.path());
    let mut quality = Vec::new();
    let mut peak = Vec::new();
    let mut fit_lines: Vec<(String, Vec<String>)> = Vec::new();
    let mut orientation_lines: Vec<(String, Mirroring)> = Vec::new();

    for case in cases {
        for &side in candidate_sides {
            let sources = load(&recipe_of(args, case, side)?, case)?;
            let analysis = sources.analyze();
            // Both builders, side by side; the host's pruned searches must give the kernels'
            // candidates bit for bit.
            let mut results = Vec::new();
            let both = args.candidates.contains(&Candidates::Gpu)
                && args.candidates.contains(&Candidates::Host);
            for (builder, baseline) in [
                (CandidateBuilder::Gpu, None),
                (CandidateBuilder::Host, both.then_some(CANDIDATES_GPU)),
            ] {
                let chosen = match builder {
                    CandidateBuilder::Gpu => Candidates::Gpu,
                    _ => Candidates::Host,
                };
                if !args.candidates.contains(&chosen) {
                    continue;
                }
                let mut last = None;
                bench.case(
                    &format!("{case} {side}² candidates"),
                    (side * side * 3) as u64,
                    if builder == CandidateBuilder::Host {
                        CANDIDATES_HOST
                    } else {
                        CANDIDATES_GPU
                    },
                    Throughput::Elements,
                    baseline,
                    || {
                        let (r, ms) = time_cpu(|| {
                            builder.compute(
                                &gpu,
                                &analysis,
                                &sources.recipe.candidates,
                                &mut |_| {},
                            )
                        });
                        last = Some(r?);
                        Ok(ms)
                    },
                )?;
                results.push(last.expect("ran at least once"));
            }
            ensure!(
                results.len() < 2 || results[0] == results[1],
                "{case} {side}²: the host's candidates differ from the GPU's"
            );
        }
        let recipe = recipe_of(args, case, args.side)?;
        let sources = load(&recipe, case)?;
        let exemplars = &sources.exemplars;
        let mirroring = sources.mirroring;
        let fits: Vec<String> = sources.fits.iter().map(ToString::to_string).collect();
        fit_lines.push((case.clone(), fits.clone()));
        orientation_lines.push((case.clone(), mirroring));
        let key = candidates_key(exemplars, &recipe.candidates);
        for (i, &n) in sizes.iter().enumerate() {
            // A variant of the recipe, prepared and synthesized at this size.
            let variant = |r: SolidRecipe| cube(&gpu, &load(&r, case)?, n, Some(&cache));
            let tag = format!("{case} {}² -> {n}³", args.side);
            let mut last = None;
            bench.case(
                &tag,
                (n as u64).pow(3),
                "lazysolid gpu synthesis (wall)",
                Throughput::Elements,
                None,
                || {
                    let (prepared, run) = cube(&gpu, &sources, n, Some(&cache))?;
                    let ms = run.synthesis_s * 1e3;
                    last = Some((prepared, run));
                    Ok(ms)
                },
            )?;
            // Cold (the entry removed first: the precompute is paid) at the first size only,
            // warm (read back) at every size.
            let mut rows = vec![(END_TO_END_WARM, CacheOutcome::Hit)];
            if i == 0 {
                rows.insert(0, (END_TO_END_COLD, CacheOutcome::Miss));
            }
            for (name, expected) in &rows {
                bench.case(
                    &tag,
                    (n as u64).pow(3),
                    name,
                    Throughput::Elements,
                    None,
                    || {
                        if *expected == CacheOutcome::Miss {
                            cache.remove(CANDIDATES_CACHE_KIND, &key)?;
                        }
                        let (run, ms) = time_cpu(|| cube(&gpu, &sources, n, Some(&cache)));
                        let (prepared, _) = run?;
                        ensure!(
                            prepared.cached == *expected,
                            "{tag} {name}: the candidate cache did {:?}",
                            prepared.cached
                        );
                        Ok(ms)
                    },
                )?;
            }
            let (prepared, run) = last.expect("ran at least once");
            let exemplars = prepared.exemplars();
            peak.push((
                format!("{case} {n}³ peak GPU MiB"),
                run.peak_bytes as f64 / 1048576.0,
            ));
            if i > 0 {
                continue;
            }
            bench.status(format!("{case}: scoring"));
            let scorers = role_scorers(exemplars);
            let q = |s: &SolidSynthesis, c: &[[u8; 3]]| {
                axis_quality(&energy, &scorers, exemplars, s, c, args.energy.samples)
            };
            let mut push = |variant: &str, axes, consistency| {
                quality.push(QualityRow {
                    case: case.clone(),
                    exemplars: fits.clone(),
                    variant: variant.into(),
                    axes,
                    consistency,
                })
            };
            let mut solid = q(&run.synthesis, &run.colours)?;
            if args.solid_seeds > 1 {
                let mut pooled: [Vec<SliceRatios>; 3] = std::array::from_fn(|a| {
                    slice_ratios(&scorers[a], &run.synthesis, &run.colours, a)
                });
                for k in 1..args.solid_seeds {
                    let seed = args.seed.wrapping_add(k);
                    bench.status(format!("{case}: scoring seed {seed}"));
                    let (_, other) = variant(SolidRecipe {
                        seed,
                        ..recipe.clone()
                    })?;
                    for (a, figures) in pooled.iter_mut().enumerate() {
                        figures.extend(slice_ratios(
                            &scorers[a],
                            &other.synthesis,
                            &other.colours,
                            a,
                        ));
                    }
                }
                for (axis, figures) in solid.iter_mut().zip(&pooled) {
                    axis.set_means(figures);
                }
            }
            push("solid", solid, Some(run.consistency));
            // The colour rule's share of the gap: each axis's slice coloured by its own role's
            // exemplar alone (a diagnostic, not a volume: the three slices disagree where the
            // voxel does), and the per-channel mean of the three.
            let triples = run.synthesis.window_triples();
            let mut own = Vec::with_capacity(3);
            for r in 0..3 {
                let colours: Vec<[u8; 3]> = triples
                    .iter()
                    .map(|t| {
                        let (x, y) = unpack(t[r]);
                        exemplars.role(r).at(x, y)
                    })
                    .collect();
                own.push(q(&run.synthesis, &colours)?[r]);
            }
            push(
                "own role",
                own.try_into().expect("three axes"),
                Some(run.consistency),
            );
            let mean: Vec<[u8; 3]> = triples
                .iter()
                .map(|t| {
                    let c: [[u8; 3]; 3] = std::array::from_fn(|r| {
                        let (x, y) = unpack(t[r]);
                        exemplars.role(r).at(x, y)
                    });
                    std::array::from_fn(|ch| {
                        ((u32::from(c[0][ch]) + u32::from(c[1][ch]) + u32::from(c[2][ch]) + 1) / 3)
                            as u8
                    })
                })
                .collect();
            push(
                "mean colour",
                q(&run.synthesis, &mean)?,
                Some(run.consistency),
            );
            // The ablations' volumes; those marked drawn go into the figures beside the
            // default's, under their variant's name.
            let mut drawn: Vec<(String, SolidCube)> = Vec::new();
            if !args.no_ablations {
                let candidates = |c: CandidateParams| SolidRecipe {
                    candidates: c,
                    ..recipe.clone()
                };
                let defaults = recipe.candidates;
                // The finest level's other correction order: ordered subpasses when the
                // default is parallel, and the reverse.
                let other_order = if DEFAULT_SOLID_PARALLEL_LEVELS > 0 {
                    0
                } else {
                    1
                };
                // (variant, drawn, recipe), in the rows' order.
                let variants: Vec<(&str, bool, SolidRecipe)> = vec![
                    (
                        "keep current",
                        true,
                        SolidRecipe {
                            schedule: SolidSchedule {
                                keep_current: true,
                                ..recipe.schedule.clone()
                            },
                            ..recipe.clone()
                        },
                    ),
                    (
                        "crossbar only",
                        false,
                        candidates(CandidateParams {
                            coherence: false,
                            ..defaults
                        }),
                    ),
                    (
                        "no balance",
                        true,
                        candidates(CandidateParams {
                            balance: 0,
                            ..defaults
                        }),
                    ),
                    (
                        "balance finest",
                        false,
                        candidates(CandidateParams {
                            balance_levels: Some(1),
                            ..defaults
                        }),
                    ),
                    (
                        "no feature",
                        true,
                        SolidRecipe {
                            feature_weight: 0,
                            ..recipe.clone()
                        },
                    ),
                    // The mask rule's ablation: Otsu's split always (the minimum-error one is
                    // taken by the rule where Otsu's takes part of the body; synth/feature.rs).
                    (
                        "otsu mask",
                        false,
                        SolidRecipe {
                            feature_mask: FeatureMask::Otsu,
                            ..recipe.clone()
                        },
                    ),
                    (
                        if other_order == 0 {
                            "ordered finest"
                        } else {
                            "parallel finest"
                        },
                        true,
                        SolidRecipe {
                            schedule: SolidSchedule {
                                parallel_levels: Some(other_order),
                                ..recipe.schedule.clone()
                            },
                            ..recipe.clone()
                        },
                    ),
                ];
                let mut runs = Vec::new();
                for (name, draw, r) in variants {
                    runs.push((name, draw, variant(r)?.1));
                }
                for (variant, draw, ablated) in runs {
                    push(
                        variant,
                        q(&ablated.synthesis, &ablated.colours)?,
                        Some(ablated.consistency),
                    );
                    if draw {
                        drawn.push((format!("-{}", variant.replace(' ', "-")), ablated));
                    }
                }
                // The orientation rule's ablation, where it mirrored a role: every role as
                // given, so that the row shows what the mirroring gains.
                if mirroring.mirrored.is_some() {
                    let (as_given, given) = {
                        let (prepared, cube) = variant(SolidRecipe {
                            orientation: Orientation::Keep,
                            ..recipe.clone()
                        })?;
                        (cube, prepared.sources.exemplars)
                    };
                    // Scored against the images as given, which its slices were made from.
                    let axes = axis_quality(
                        &energy,
                        &role_scorers(&given),
                        &given,
                        &as_given.synthesis,
                        &as_given.colours,
                        args.energy.samples,
                    )?;
                    push("as given", axes, Some(as_given.consistency));
                    drawn.push(("-as-given".into(), as_given));
                }
            }
            let (ex, ex_colours) = extruded(exemplars, n);
            push("extruded E_z", q(&ex, &ex_colours)?, None);
            let (two_d, image) = synth_2d(
                &gpu,
                &energy,
                &scorers,
                exemplars,
                n,
                args.seed,
                args.energy.samples,
            )?;
            push("2d synth", two_d, None);
            let name = case.replace('+', "-");
            for (variant, s) in
                std::iter::once(("", &run)).chain(drawn.iter().map(|(v, r)| (v.as_str(), r)))
            {
                let (w, h, rgb) = figure(exemplars.role(0), &image, &s.synthesis, &s.colours);
                write_png(
                    &dir.join(format!("{name}-{n}{variant}-slices.png")),
                    w,
                    h,
                    &rgb,
                )?;
            }
            let (sw, sh, slab) = &run.slab;
            write_png(&dir.join(format!("{name}-slab.png")), *sw, *sh, slab)?;
        }
    }

    for (case, fits) in &fit_lines {
        println!("{case}: exemplar fit: {}", fits.join("; "));
    }
    for (case, mirroring) in &orientation_lines {
        println!("{case}: orientation: {mirroring}");
    }
    println!(
        "{:<28} {:<14} {}  {:>6} {:>6}",
        "case",
        "variant",
        (0..3)
            .map(|a| format!(
                "{:>7} {:>5} {:>5} {:>6} {:>5} {:>5} {:>8}",
                format!("SWDr {}", ROLE_NAMES[a]),
                "SWD8",
                "block",
                "diag",
                "hist",
                "rep",
                "E"
            ))
            .collect::<Vec<_>>()
            .join("  "),
        "cand%",
        "spread"
    );
    let mut csv = String::from(
        "case,variant,axis,swd,swd_ratio,blockiness,energy,histogram,repetition,anisotropy,exemplar_anisotropy,diagonal,exemplar_diagonal,slices_swd_ratio,slices_swd_ratio_sd,slices_blockiness,slices_swd_band_fine,slices_swd_band_mid,slices_swd_band_coarse,slices_band_contrast_fine,slices_band_contrast_mid,slices_band_contrast_coarse,candidate_share,spread,candidate_spread,in_plane_coherence,advance_closure\n",
    );
    for row in &quality {
        let (share, spread) = row.consistency.map_or((String::new(), String::new()), |c| {
            (
                format!("{:.1}", 100.0 * c.candidate_share),
                format!("{:.1}", c.spread),
            )
        });
        println!(
            "{:<28} {:<14} {}  {:>6} {:>6}",
            row.case,
            row.variant,
            row.axes
                .iter()
                .map(|q| format!(
                    "{:>7.2} {:>5.2} {:>5.2} {:>+6.2} {:>5.3} {:>5.2} {:>8.1}",
                    q.swd_ratio,
                    q.slices_swd_ratio,
                    q.blockiness,
                    q.diagonal,
                    q.histogram,
                    q.repetition,
                    q.energy
                ))
                .collect::<Vec<_>>()
                .join("  "),
            share,
            spread
        );
        for (a, q) in row.axes.iter().enumerate() {
            let c = row.consistency.map_or(",,,,".to_string(), |c| {
                format!(
                    "{:.4},{:.2},{:.2},{:.4},{:.4}",
                    c.candidate_share,
                    c.spread,
                    c.candidate_spread,
                    c.in_plane_coherence[a],
                    c.advance_closure[a]
                )
            });
            csv.push_str(&format!(
                "{},{},{},{:.3},{:.3},{:.3},{:.3},{:.5},{:.4},{:.4},{:.4},{:.4},{:.4},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{c}\n",
                row.case,
                row.variant,
                ["x", "y", "z"][a],
                q.swd,
                q.swd_ratio,
                q.blockiness,
                q.energy,
                q.histogram,
                q.repetition,
                q.anisotropy,
                q.exemplar_anisotropy,
                q.diagonal,
                q.exemplar_diagonal,
                q.slices_swd_ratio,
                q.slices_swd_ratio_sd,
                q.slices_blockiness,
                q.slices_swd_bands[0],
                q.slices_swd_bands[1],
                q.slices_swd_bands[2],
                q.slices_band_contrast[0],
                q.slices_band_contrast[1],
                q.slices_band_contrast[2]
            ));
        }
    }
    write_bytes_atomically(&dir.join("quality.csv"), csv.as_bytes())?;
    write_bytes_atomically(
        &dir.join("quality.json"),
        serde_json::to_string_pretty(&quality)?.as_bytes(),
    )?;
    bench.finish(&peak)?;
    println!("quality table and figures in {}", dir.display());
    Ok(())
}
