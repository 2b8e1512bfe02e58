//! `lazysolid bench multiscale`: the multiscale synthesizer's throughput against the
//! single-exemplar synthesizer on the root exemplar (same device, same run, same output size;
//! the paper's ratio is 9.37 / 15.30 = 0.61×), the graph analysis time, and per-scale quality:
//! for every synthesis depth, the neighbourhood energy and the period repetition of the output
//! against the stack level that governs most of its pixels. See docs/multiscale.md.

use super::harness::{Bench, Throughput};
use super::CommonArgs;
use crate::cli::assets::load_graph;
use crate::cli::output::write_atomically;
use crate::cli::resolution::Resolution;
use crate::cli::tuning::Energy;
use crate::cli::GlobalArgs;
use clap::Args;
use lazysolid_compute::atomic_file::write_bytes_atomically;
use lazysolid_synth::multiscale::{
    analyze_graph, colour, MultiscaleAnalysis, MultiscaleGpu, MultiscaleParams, PixelState,
};
use lazysolid_synth::{
    analyze, default_jitter, default_passes, unpack, AnalysisParams, GpuSynthesizer, Region,
    SynthParams, DEFAULT_PERIOD_PENALTY, REPETITION_TOLERANCE,
};
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

/// Options of the suite.
#[derive(Args)]
#[command(mut_arg("samples", |a| a
    .default_value("256")
    .help("Energy samples per depth, a regular subgrid of each quality window: 256 here (4096 in \
           the other commands), since every depth of the zoom is scored")))]
pub struct MultiscaleBenchArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Exemplar graphs (TOML).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "scenes/multiscale/parquet_walnut.toml,scenes/multiscale/marble_loop.toml"
    )]
    pub graphs: Vec<PathBuf>,
    /// Output size of the timed windows, WxH in pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "256x256")]
    pub res: Resolution,
    /// Depths past the root's finest level also timed (against the same 2D baseline).
    #[arg(long, default_value_t = 2)]
    pub deeper: u32,
    /// Size of the per-depth quality windows, WxH in pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "128x128")]
    pub quality_res: Resolution,
    #[command(flatten)]
    pub energy: Energy,
    /// Seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
}

/// Energy radius (7×7, as the 2D synthesizer's energy).
const R: i32 = 3;

/// Mean over sampled output pixels of the smallest squared RGB distance between the output's
/// 7×7 neighbourhood and a 7×7 neighbourhood of the stack level sampled at its spacing `h`
/// (what one output pixel step is at that level), over every texel of the level.
fn level_energy(
    analysis: &MultiscaleAnalysis,
    exemplar: usize,
    level: u32,
    out: &[[u8; 3]],
    size: Resolution,
    samples: usize,
) -> f64 {
    let e = &analysis.exemplars[exemplar];
    let h = 1i32 << (e.finest - level);
    let img = &e.stack[level as usize];
    let (w, hh) = (e.width as i32, e.height as i32);
    let per_axis = (samples as f64).sqrt().ceil() as i32;
    let (out_w, span_x, span_y) = (
        size.width as i32,
        size.width as i32 - 2 * R,
        size.height as i32 - 2 * R,
    );
    let positions: Vec<(i32, i32)> = (0..per_axis)
        .flat_map(|j| {
            (0..per_axis).map(move |i| {
                (
                    R + i * span_x / per_axis.max(1),
                    R + j * span_y / per_axis.max(1),
                )
            })
        })
        .collect();
    let total: u64 = positions
        .par_iter()
        .map(|&(px, py)| {
            let mut best = u64::MAX;
            for vy in 0..hh {
                for vx in 0..w {
                    let mut d = 0u64;
                    'n: for dy in -R..=R {
                        for dx in -R..=R {
                            let o = out[((py + dy) * out_w + px + dx) as usize];
                            let sx = (vx + dx * h).rem_euclid(w);
                            let sy = (vy + dy * h).rem_euclid(hh);
                            let s = img[(sy * w + sx) as usize];
                            for c in 0..3 {
                                let t = o[c] as i64 - s[c] as i64;
                                d += (t * t) as u64;
                            }
                            if d >= best {
                                break 'n;
                            }
                        }
                    }
                    best = best.min(d);
                }
            }
            best
        })
        .sum();
    total as f64 / positions.len() as f64
}

/// Share of output pixel pairs one period of the governing level apart (`w / h` output
/// pixels) at that same level whose coordinates lie within the repetition tolerance.
fn level_repetition(
    analysis: &MultiscaleAnalysis,
    states: &[PixelState],
    size: Resolution,
    meta: u32,
) -> f64 {
    let s0 = states.iter().find(|s| s.meta == meta).expect("governing");
    let e = &analysis.exemplars[s0.exemplar()];
    let h = 1u32 << (e.finest - s0.level());
    let (px, py) = ((e.width / h) as usize, (e.height / h) as usize);
    let (n, rows) = (size.width as usize, size.height as usize);
    let (mut pairs, mut equal) = (0u64, 0u64);
    let near = |a: &PixelState, b: &PixelState| {
        let (ax, ay) = unpack(a.coord);
        let (bx, by) = unpack(b.coord);
        let d = |p: u32, q: u32, m: u32| {
            let d = p.abs_diff(q);
            d.min(m - d)
        };
        d(ax, bx, e.width).max(d(ay, by, e.height)) <= REPETITION_TOLERANCE
    };
    for y in 0..rows {
        for x in 0..n {
            let a = &states[y * n + x];
            if a.meta != meta {
                continue;
            }
            for (qx, qy) in [(x + px, y), (x, y + py)] {
                if px == 0 || py == 0 || qx >= n || qy >= rows {
                    continue;
                }
                let b = &states[qy * n + qx];
                if b.meta == meta {
                    pairs += 1;
                    equal += u64::from(near(a, b));
                }
            }
        }
    }
    if pairs == 0 {
        f64::NAN
    } else {
        equal as f64 / pairs as f64
    }
}

/// Runs the suite.
pub fn run(args: &MultiscaleBenchArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let gpu = global.gpu()?;
    let cases = args.graphs.len() as u64 * (2 + args.deeper as u64);
    let mut bench = Bench::new("multiscale", &gpu, &args.common, cases)?;
    let mut notes = Vec::new();
    let mut quality = Vec::new();
    for path in &args.graphs {
        let graph = load_graph(path)?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        bench.status(format!("{name}: analysis"));
        let start = Instant::now();
        let analysis = analyze_graph(&graph, &AnalysisParams::default())?;
        let analysis_s = start.elapsed().as_secs_f64();
        notes.push((format!("{name} analysis (CPU, s)"), analysis_s));
        notes.push((
            format!("{name} distinct depth sets"),
            analysis.sets.len() as f64,
        ));
        let ms = MultiscaleGpu::new(&gpu, &analysis)?;
        let root = &graph.exemplars[graph.topology.root];
        let flat = analyze(root, &AnalysisParams::default())?;
        let levels = flat.levels.len() as u32;
        let p2 = SynthParams::new(
            levels,
            args.seed,
            &default_passes(levels),
            &default_jitter(levels),
        )?;
        let single = GpuSynthesizer::new(&gpu, &flat)?;
        let window = Region {
            origin: [0, 0],
            size: [args.res.width, args.res.height],
        };
        let pixels = args.res.width as u64 * args.res.height as u64;
        let finest = root.finest_level();
        for depth in finest..=finest + args.deeper {
            let case = format!("{name} {} depth {depth}", args.res);
            bench.case(
                &case,
                pixels,
                "2D synthesizer, root exemplar (gpu passes)",
                Throughput::Elements,
                None,
                || {
                    let (_, times) =
                        single.synthesize_timed(&flat, &p2, window, false, &mut |_| {})?;
                    Ok(times.iter().map(|t| t.upsample_ms + t.correct_ms).sum())
                },
            )?;
            let pm = MultiscaleParams::new(args.seed, depth, &[], &[], DEFAULT_PERIOD_PENALTY)?;
            bench.case(
                &case,
                pixels,
                "multiscale (gpu passes)",
                Throughput::Elements,
                Some("2D synthesizer, root exemplar (gpu passes)"),
                || {
                    let (_, times) = ms.synthesize(&analysis, &pm, window, false)?;
                    Ok(times.iter().map(|t| t.upsample_ms + t.correct_ms).sum())
                },
            )?;
        }
        // Per-scale quality.
        let q = args.quality_res;
        let qwin = Region {
            origin: [0, 0],
            size: [q.width, q.height],
        };
        for depth in 0..=finest + args.deeper {
            bench.status(format!("{name}: quality at depth {depth}"));
            let pm = MultiscaleParams::new(args.seed, depth, &[], &[], DEFAULT_PERIOD_PENALTY)?;
            let (out, _) = ms.synthesize(&analysis, &pm, qwin, false)?;
            let states = out.window_states();
            let mut counts = std::collections::BTreeMap::<u32, usize>::new();
            for s in &states {
                *counts.entry(s.meta).or_default() += 1;
            }
            let (&meta, &count) = counts
                .iter()
                .max_by_key(|(m, c)| (**c, std::cmp::Reverse(**m)))
                .expect("pixels");
            let s0 = *states.iter().find(|s| s.meta == meta).expect("governing");
            let e = &analysis.exemplars[s0.exemplar()];
            let level = s0.level().min(e.finest);
            let colours: Vec<[u8; 3]> = states.iter().map(|s| colour(&analysis, s)).collect();
            let energy = level_energy(
                &analysis,
                s0.exemplar(),
                level,
                &colours,
                q,
                args.energy.samples,
            );
            // The same pixels without their transfers: the stack texels alone, which the
            // governing level's energy measures apart from the colour adaptation.
            let raw: Vec<[u8; 3]> = states
                .iter()
                .map(|s| {
                    colour(
                        &analysis,
                        &PixelState {
                            transfer: [0; 3],
                            ..*s
                        },
                    )
                })
                .collect();
            let energy_untransferred = level_energy(
                &analysis,
                s0.exemplar(),
                level,
                &raw,
                q,
                args.energy.samples,
            );
            let repetition = if s0.magnified() {
                f64::NAN
            } else {
                level_repetition(&analysis, &states, q, meta)
            };
            quality.push(QualityRow {
                graph: name.clone(),
                depth,
                exemplar: graph.names[s0.exemplar()].clone(),
                level,
                magnified: s0.magnified(),
                share: count as f64 / states.len() as f64,
                energy,
                energy_untransferred,
                repetition,
            });
        }
    }
    let dir = bench.artifact_dir()?;
    let qpath = dir.join("quality.csv");
    write_atomically(&qpath, |f| {
        let mut w = csv::Writer::from_writer(f);
        for r in &quality {
            w.serialize(r)?;
        }
        Ok(w.flush()?)
    })?;
    write_bytes_atomically(
        &dir.join("quality.json"),
        serde_json::to_string_pretty(&quality)?.as_bytes(),
    )?;
    println!(
        "per-scale quality ({} windows at the origin):",
        args.quality_res
    );
    println!(
        "graph, depth, governing exemplar level (share of pixels), energy per 7x7 (displayed / \
         without transfers), repetition"
    );
    for r in &quality {
        println!(
            "  {:16} depth {:2}: {} level {}{} ({:5.1} %)  energy {:9.1} / {:9.1}  repetition {:.3}",
            r.graph,
            r.depth,
            r.exemplar,
            r.level,
            if r.magnified { " magnified" } else { "" },
            100.0 * r.share,
            r.energy,
            r.energy_untransferred,
            r.repetition
        );
    }
    println!("quality table: {}", qpath.display());
    bench.finish(&notes)?;
    Ok(())
}

/// One depth's quality.
#[derive(serde::Serialize)]
struct QualityRow {
    graph: String,
    depth: u32,
    exemplar: String,
    level: u32,
    magnified: bool,
    share: f64,
    energy: f64,
    energy_untransferred: f64,
    repetition: f64,
}
