//! `lazysolid bench glints`: the glint microstructure by example: its range-query structure,
//! its memory and its material's render time. The suite has parts, chosen with `--part`, that
//! join one table:
//!
//! - **structures**: range min/max queries over the example, per example size n (target patch
//!   l = n / 4): the square-only sparse table (one lookup) against a min–max mip hierarchy (the
//!   union of the square's maximal aligned blocks) and brute force (every texel of the
//!   square). Bytes, build time (CPU, one thread, against the device's dispatches by GPU
//!   timestamps; uploads excluded) and query rate (CPU, one thread, and GPU timestamps) over
//!   one batch of random squares (random levels 0..=log2 l and starts, fixed seed). All six
//!   answer vectors must be identical, and both device-built structures equal their CPU
//!   builds; the suite stops otherwise.
//! - **render**: the glint material's render time on a scene (`scenes/glints.toml`): the
//!   pruned traversal against the explicit reference (every texel of each footprint, the
//!   ratio the paper reports as +3 % to +53 %) and against the plain conductor.
//! - **memory**: the constant storage of the method (the example as 2 × f32 per texel, the
//!   sparse table, the Gaussianization tables) against the materialized normal map the
//!   explicit method needs for a coverage of C² texels (2 × f32 per texel and its 16-bit
//!   min–max mip), beside the paper's Table 1 (35 MB against 7,896 MB for the Chair's 5K² map:
//!   0.44 %; against 1,119.9 MB for the Kettle's 2K² map: 3.1 %).
//!
//! Examples: an image (the assets' exemplars or a path) read as a height map (luminance times
//! `--relief` texels), cropped to N² where it is at least that large; sizes the image lacks use
//! a deterministic generated height field of bumps and scratches. The table's case names say
//! which.

use super::harness::{time_cpu, time_gpu, Bench, Throughput};
use super::plot::bar_chart;
use super::CommonArgs;
use crate::cli::resolution::Resolution;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::{Args, ValueEnum};
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::glint::minmax_mip::{
    brute_force, minmax_mip_bytes, random_squares, table_query, MinMaxMip,
};
use lazysolid_renderer::glint::range_table::quantize_texels;
use lazysolid_renderer::glint::synthetic::{bumps_and_scratches, BumpExtent};
use lazysolid_renderer::glint::GlintCase;
use lazysolid_renderer::glint::{
    gpu_range_query::range_query_kernel, record_range_queries, record_range_table, GaussianTables,
    GpuMinMaxMip, NormalExample, RangeMethod, RangeTable,
};
use lazysolid_renderer::kernels::render::GLINT_RANGE_LEVEL;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{MaterialKind, Scene};
use lazysolid_synth::Exemplar;
use std::path::PathBuf;
use std::time::Duration;

/// Which parts of the suite run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum GlintsPart {
    /// Range-query structures: bytes, build time, query rate.
    Structures,
    /// Constant storage against the explicit method's materialized map.
    Memory,
    /// The glint material's render time against the explicit reference and the conductor.
    Render,
    /// Every part.
    All,
}

/// What to measure.
#[derive(Args)]
pub struct GlintsArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// The parts to run.
    #[arg(long, value_enum, default_value_t = GlintsPart::All)]
    pub part: GlintsPart,
    /// Example sizes, one set of cases each (square: N or NxN, a power of two from 16 to
    /// 2048); the target patch is l = N / 4.
    #[arg(
        long,
        value_name = "WxH",
        value_delimiter = ',',
        default_value = "128,256,512"
    )]
    pub res: Vec<Resolution>,
    /// The example's height map: a name in the assets' exemplars, a path to a PNG (8 or 16
    /// bits, any size) or a GIMP pattern, or `generated` (bumps and scratches at every size).
    #[arg(long, default_value = "crinklepaper")]
    pub exemplar: String,
    /// Where named exemplars live; default: the assets' exemplars.
    #[arg(long, value_name = "DIR")]
    pub exemplar_dir: Option<PathBuf>,
    /// Height of the image's full luminance range, in texels.
    #[arg(long, default_value_t = 4.0)]
    pub relief: f32,
    /// Random squares per query batch.
    #[arg(long, default_value_t = 1 << 18)]
    pub queries: usize,
    /// Seed of the query batch and of generated examples.
    #[arg(long, default_value_t = 18)]
    pub seed: u64,
    /// Edges C of the materialized maps of the explicit method (C² texels): the paper's Chair
    /// (5K², 10 widths of a 512² example) and Kettle (2K²).
    #[arg(long, value_delimiter = ',', default_value = "5120,2048")]
    pub coverage: Vec<u64>,
    /// The scene of the render part (its glint materials are rendered pruned, explicit and as
    /// their plain conductor).
    #[arg(long, value_name = "FILE", default_value = "scenes/glints.toml")]
    pub scene: PathBuf,
    /// Pixels of the render part's images.
    #[arg(long, value_name = "WxH", default_value = "128x96")]
    pub render_res: Resolution,
    /// Samples per pixel of the render part.
    #[arg(long, default_value_t = 8)]
    pub spp: u32,
    /// One size (the first), 2^14 queries, renders at 64×48 with 2 samples per pixel.
    #[arg(long)]
    pub quick: bool,
}

/// The paper's Table 1 (MB): its constant storage for a 512² example, and the explicit maps.
const PAPER_OURS_MB: f64 = 35.0;
const PAPER_EXPLICIT: [(u64, f64, &str); 2] = [(5120, 7896.0, "Chair"), (2048, 1119.9, "Kettle")];

/// Bytes per texel of Yan et al. 2016's explicit map in the paper: 7,896 MB for 5120².
const YAN16_BYTES_PER_TEXEL: f64 = 7896.0e6 / (5120.0 * 5120.0);

/// An example and where it came from.
struct Example {
    example: NormalExample,
    source: String,
}

/// The height map image: its luminance (0..1), row by row.
struct HeightImage {
    name: String,
    width: usize,
    height: usize,
    luma: Vec<f32>,
}

/// The `--exemplar` image, or `None` for `generated`.
fn load_image(args: &GlintsArgs) -> anyhow::Result<Option<HeightImage>> {
    if args.exemplar == "generated" {
        return Ok(None);
    }
    let path = assets::exemplar("--exemplar", &args.exemplar, args.exemplar_dir.as_deref())?;
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
fn example_of(
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
fn short_source(e: &Example, image: Option<&HeightImage>) -> String {
    match image {
        Some(i) if e.source.starts_with(i.name.as_str()) => i.name.clone(),
        _ => "generated".into(),
    }
}

/// What the structures part measured for one size (for the summary and the figures).
struct SizeResult {
    label: String,
    table_bytes: u64,
    mip_bytes: u64,
    texel_bytes: u64,
    build_ms: [f64; 4],
    /// Mquery/s: sparse table, mip, brute force; CPU then GPU.
    rates: [[f64; 3]; 2],
    mean_blocks: f64,
    mean_texels: f64,
}

/// Runs the suite.
pub fn run(args: &GlintsArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let res = if args.quick {
        &args.res[..args.res.len().min(1)]
    } else {
        &args.res[..]
    };
    let queries = if args.quick { 1 << 14 } else { args.queries };
    ensure!(!res.is_empty(), "--res needs a value");
    let mut sizes = Vec::new();
    for r in res {
        let n = r.side("--res", "a glint example")? as usize;
        ensure!(
            n.is_power_of_two() && (16..=2048).contains(&n),
            "--res {r}: the example edge must be a power of two in 16..=2048 (its target \
             patch N / 4 needs at least 4 texels)"
        );
        sizes.push(n);
    }
    ensure!(
        (1..=1 << 24).contains(&queries),
        "--queries {queries}: must lie in 1..=16777216"
    );
    ensure!(
        args.relief.is_finite() && args.relief > 0.0,
        "--relief {}: must be positive",
        args.relief
    );
    ensure!(
        args.coverage.iter().all(|&c| (1..=1 << 20).contains(&c)),
        "--coverage: edges must lie in 1..=1048576"
    );
    let structures = matches!(args.part, GlintsPart::Structures | GlintsPart::All);
    let memory = matches!(args.part, GlintsPart::Memory | GlintsPart::All);
    let render = matches!(args.part, GlintsPart::Render | GlintsPart::All);
    let scene = if render {
        Some(render_scene(args)?)
    } else {
        None
    };
    let image = load_image(args)?;
    let gpu = global.gpu()?;
    let cases = if structures { 10 * sizes.len() } else { 0 }
        + if render { GlintCase::ALL.len() } else { 0 };
    let mut bench = Bench::new("bench-glints", &gpu, &args.common, cases as u64)?;
    let mut notes: Vec<(String, f64)> = Vec::new();
    let mut results = Vec::new();
    let mut storage = Vec::new();
    for &n in &sizes {
        bench.status(format!("{n}²: preparing the example"));
        let ex = example_of(n, image.as_ref(), args)?;
        let label = format!("{n}² {}", short_source(&ex, image.as_ref()));
        eprintln!("{label}: {}", ex.source);
        let patch = (n / 4) as u32;
        let levels = patch.trailing_zeros() as usize + 1;
        let texel_bytes = (n * n * 8) as u64;
        let table_bytes = (levels * n * n * 8) as u64;
        let gauss_bytes = (GaussianTables::new(&ex.example).device_knots().len() * 4) as u64;
        storage.push((label.clone(), patch, texel_bytes, table_bytes, gauss_bytes));
        if structures {
            results.push(measure_structures(
                &mut bench, &gpu, &ex, &label, patch, queries, args.seed, &mut notes,
            )?);
        }
    }
    if structures {
        print_structures(&results, queries);
        figures(&bench, &results)?;
    }
    if memory {
        memory_part(&storage, &args.coverage, &mut notes);
    }
    if let Some(scene) = &scene {
        render_part(&mut bench, &gpu, scene, args, &mut notes)?;
    }
    bench.finish(&notes)?;
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn measure_structures(
    bench: &mut Bench,
    gpu: &lazysolid_compute::gpu::Gpu,
    ex: &Example,
    label: &str,
    patch: u32,
    queries: usize,
    seed: u64,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<SizeResult> {
    let e = &ex.example;
    let n = e.size();
    let levels = patch.trailing_zeros() as usize + 1;
    const CPU: &str = "cpu (1 thread)";
    const GPU: &str = "gpu (device time)";

    // Builds: the CPU references, then the device's dispatches over uploaded texels.
    let case = format!("{label} sparse table build");
    let mut cpu_table = None;
    let table_cpu_ms = bench.case(
        &case,
        (levels * n * n) as u64,
        CPU,
        Throughput::Items("entry"),
        None,
        || {
            let (t, ms) = time_cpu(|| RangeTable::build(e, patch));
            cpu_table = Some(t);
            Ok(ms)
        },
    )?;
    let cpu_table = cpu_table.context("no CPU table")?;
    let texels = GpuBuffer::from_slice(gpu, "glint bench texels", &quantize_texels(e))?;
    let table = GpuBuffer::<[u32; 2]>::new(gpu, "glint bench table", levels * n * n)?;
    let level_kernel = gpu.kernel(&GLINT_RANGE_LEVEL)?;
    let table_gpu_ms = bench.case(
        &case,
        (levels * n * n) as u64,
        GPU,
        Throughput::Items("entry"),
        Some(CPU),
        || {
            time_gpu(gpu, |rec| {
                record_range_table(rec, &level_kernel, &texels, &table, n, levels)
            })
        },
    )?;
    ensure!(
        RangeTable::from_entries(n, levels, table.read()?) == cpu_table,
        "{case}: the device table differs from the CPU build"
    );
    drop(texels);
    let case = format!("{label} min–max mip build");
    let mip_entries = MinMaxMip::entry_count(n) as u64;
    let mut cpu_mip = None;
    let mip_cpu_ms = bench.case(
        &case,
        mip_entries,
        CPU,
        Throughput::Items("entry"),
        None,
        || {
            let (m, ms) = time_cpu(|| MinMaxMip::build(e));
            cpu_mip = Some(m);
            Ok(ms)
        },
    )?;
    let cpu_mip = cpu_mip.context("no CPU mip")?;
    let mip = GpuMinMaxMip::new(gpu, e)?;
    let mip_gpu_ms = bench.case(
        &case,
        mip_entries,
        GPU,
        Throughput::Items("entry"),
        Some(CPU),
        || time_gpu(gpu, |rec| mip.record_build(rec)),
    )?;
    ensure!(
        mip.to_host()? == cpu_mip,
        "{case}: the device mip differs from the CPU build"
    );

    // Queries: one batch, every method on the CPU and the device, all answers identical.
    let squares = random_squares(n, levels, queries, seed);
    let quantized = quantize_texels(e);
    let (mut blocks, mut texels_read) = (0u64, 0u64);
    // Per level: squares and mip blocks (the mip's cost grows with the edge).
    let mut per_level = vec![(0u64, 0u64); levels];
    for q in &squares {
        let b = cpu_mip.query_counted(*q).1 as u64;
        blocks += b;
        per_level[q.level as usize].0 += 1;
        per_level[q.level as usize].1 += b;
        texels_read += ((1u64 << q.level) + 1).pow(2);
    }
    for (k, (count, b)) in per_level.iter().enumerate() {
        notes.push((
            format!("{label}: mean mip blocks per query at level {k}"),
            *b as f64 / (*count).max(1) as f64,
        ));
    }
    let case = format!("{label} query");
    let q = queries as u64;
    let baseline = |m: RangeMethod| match m {
        RangeMethod::SparseTable => Some(RangeMethod::MinMaxMip),
        RangeMethod::MinMaxMip => Some(RangeMethod::BruteForce),
        RangeMethod::BruteForce => None,
    };
    let cpu_name = |m: RangeMethod| format!("{} (cpu, 1 thread)", m.name());
    let gpu_name = |m: RangeMethod| format!("{} (gpu)", m.name());
    let mut answers: Vec<(String, Vec<[u32; 2]>)> = Vec::new();
    let mut rates = [[0.0; 3]; 2];
    for (k, m) in RangeMethod::ALL.into_iter().enumerate() {
        let mut out = Vec::new();
        let ms = bench.case(
            &case,
            q,
            &cpu_name(m),
            Throughput::Items("query"),
            baseline(m).map(cpu_name).as_deref(),
            || {
                let (r, ms) = time_cpu(|| -> Vec<[u32; 2]> {
                    match m {
                        RangeMethod::SparseTable => squares
                            .iter()
                            .map(|s| table_query(&cpu_table, *s))
                            .collect(),
                        RangeMethod::MinMaxMip => {
                            squares.iter().map(|s| cpu_mip.query(*s)).collect()
                        }
                        RangeMethod::BruteForce => squares
                            .iter()
                            .map(|s| brute_force(&quantized, n, *s))
                            .collect(),
                    }
                });
                out = r;
                Ok(ms)
            },
        )?;
        rates[0][k] = q as f64 / ms / 1e3;
        answers.push((cpu_name(m), out));
    }
    let square_buf = GpuBuffer::from_slice(gpu, "glint bench squares", &squares)?;
    let result_buf = GpuBuffer::<[u32; 2]>::new(gpu, "glint bench answers", queries)?;
    let kernel = range_query_kernel(gpu)?;
    for (k, m) in RangeMethod::ALL.into_iter().enumerate() {
        // Brute force reads the quantized texels: the mip's level 0.
        let structure = match m {
            RangeMethod::SparseTable => &table,
            _ => &mip.entries,
        };
        let ms = bench.case(
            &case,
            q,
            &gpu_name(m),
            Throughput::Items("query"),
            baseline(m).map(gpu_name).as_deref(),
            || {
                time_gpu(gpu, |rec| {
                    record_range_queries(
                        rec,
                        &kernel,
                        m,
                        structure,
                        n,
                        &square_buf,
                        &result_buf,
                        queries,
                    )
                })
            },
        )?;
        rates[1][k] = q as f64 / ms / 1e3;
        answers.push((gpu_name(m), result_buf.read()?));
    }
    let (first, reference) = &answers[0];
    for (name, a) in &answers[1..] {
        if let Some(i) = (0..queries).find(|&i| a[i] != reference[i]) {
            anyhow::bail!(
                "{case}: {name} answers {:08x?} for square {:?}, {first} answers {:08x?}",
                a[i],
                squares[i],
                reference[i]
            );
        }
    }
    let mean_blocks = blocks as f64 / q as f64;
    let mean_texels = texels_read as f64 / q as f64;
    for (what, v) in [
        ("levels (0..=log2 l)", levels as f64),
        ("example texels bytes (2 x f32)", (n * n * 8) as f64),
        ("sparse table bytes", cpu_table.bytes() as f64),
        ("min–max mip bytes", cpu_mip.bytes() as f64),
        ("brute force bytes (quantized texels)", (n * n * 8) as f64),
        ("mean mip blocks per query", mean_blocks),
        ("mean texels per query (brute force)", mean_texels),
        ("gpu sparse table over mip (min)", rates[1][0] / rates[1][1]),
        (
            "gpu sparse table over brute force (min)",
            rates[1][0] / rates[1][2],
        ),
        ("cpu sparse table over mip (min)", rates[0][0] / rates[0][1]),
        (
            "cpu sparse table over brute force (min)",
            rates[0][0] / rates[0][2],
        ),
    ] {
        notes.push((format!("{label}: {what}"), v));
    }
    eprintln!("{label}: {queries} squares, all 6 answer sets identical");
    Ok(SizeResult {
        label: label.into(),
        table_bytes: cpu_table.bytes(),
        mip_bytes: cpu_mip.bytes(),
        texel_bytes: (n * n * 8) as u64,
        build_ms: [table_cpu_ms, table_gpu_ms, mip_cpu_ms, mip_gpu_ms],
        rates,
        mean_blocks,
        mean_texels,
    })
}

fn mib(b: u64) -> f64 {
    b as f64 / (1u64 << 20) as f64
}

fn print_structures(results: &[SizeResult], queries: usize) {
    println!(
        "range queries ({queries} random squares per size, levels 0..=log2(n/4), answers \
         identical across methods and devices):"
    );
    println!(
        "{:<22} {:<13} {:>9} {:>10} {:>10} {:>12} {:>12} {:>14}",
        "example",
        "structure",
        "MiB",
        "build cpu",
        "build gpu",
        "cpu Mq/s",
        "gpu Mq/s",
        "reads/query"
    );
    for r in results {
        let rows = [
            (
                "sparse table",
                r.table_bytes,
                format!("{:.2} ms", r.build_ms[0]),
                format!("{:.2} ms", r.build_ms[1]),
                1.0,
            ),
            (
                "min–max mip",
                r.mip_bytes,
                format!("{:.2} ms", r.build_ms[2]),
                format!("{:.2} ms", r.build_ms[3]),
                r.mean_blocks,
            ),
            (
                "brute force",
                r.texel_bytes,
                "-".into(),
                "-".into(),
                r.mean_texels,
            ),
        ];
        for (k, (name, bytes, cpu, gpu, reads)) in rows.into_iter().enumerate() {
            println!(
                "{:<22} {:<13} {:>9.2} {:>10} {:>10} {:>12.2} {:>12.2} {:>14.1}",
                r.label,
                name,
                mib(bytes),
                cpu,
                gpu,
                r.rates[0][k],
                r.rates[1][k],
                reads
            );
        }
    }
}

fn figures(bench: &Bench, results: &[SizeResult]) -> anyhow::Result<()> {
    let dir = bench.artifact_dir()?;
    let categories: Vec<String> = results.iter().map(|r| r.label.clone()).collect();
    let mut series = Vec::new();
    for (d, device) in ["cpu", "gpu"].iter().enumerate() {
        for (k, m) in RangeMethod::ALL.iter().enumerate() {
            series.push((
                format!("{} ({device})", m.name()),
                // kquery/s: the log axis starts at 0.5, above brute force's Mquery/s.
                results.iter().map(|r| r.rates[d][k] * 1e3).collect(),
            ));
        }
    }
    bar_chart(
        &dir.join("glints-queries.png"),
        "range queries over random squares (min time)",
        "example",
        "kquery/s",
        &categories,
        &series,
        true,
    )?;
    bar_chart(
        &dir.join("glints-bytes.png"),
        "range-query structure bytes",
        "example",
        "MiB",
        &categories,
        &[
            (
                "sparse table".into(),
                results.iter().map(|r| mib(r.table_bytes)).collect(),
            ),
            (
                "min–max mip".into(),
                results.iter().map(|r| mib(r.mip_bytes)).collect(),
            ),
            (
                "quantized texels (brute force)".into(),
                results.iter().map(|r| mib(r.texel_bytes)).collect(),
            ),
        ],
        false,
    )?;
    Ok(())
}

/// Bytes of the explicit method's materialized map of `edge`² texels: (n_x, n_y) as 2 × f32
/// and the 16-bit min–max mip over it.
fn explicit_bytes(edge: u64) -> u64 {
    edge * edge * 8 + minmax_mip_bytes(edge)
}

fn memory_part(
    storage: &[(String, u32, u64, u64, u64)],
    coverage: &[u64],
    notes: &mut Vec<(String, f64)>,
) {
    println!(
        "memory: constant storage (example 2 x f32 per texel + sparse table + Gaussianization \
         tables) against the explicit method's materialized map (2 x f32 per texel + 16-bit \
         min–max mip), MB = 10^6 bytes:"
    );
    println!(
        "{:<22} {:>5} {:>9} {:>9} {:>8} {:>9} {:>10} {:>11} {:>8} {:>13} {:>14}",
        "example",
        "l",
        "example",
        "table",
        "tables",
        "total",
        "coverage",
        "explicit",
        "ratio",
        "ratio @Yan16",
        "paper"
    );
    let mb = |b: u64| b as f64 / 1e6;
    for (label, patch, texels, table, gauss) in storage {
        let total = texels + table + gauss;
        notes.push((format!("{label}: constant storage bytes"), total as f64));
        notes.push((
            format!("{label}: gaussianization table bytes"),
            *gauss as f64,
        ));
        for &c in coverage {
            let explicit = explicit_bytes(c);
            let ratio = total as f64 / explicit as f64 * 100.0;
            // The explicit map at Yan et al.'s bytes per texel (the Chair's 7,896 MB / 5120²).
            let yan = total as f64 / (YAN16_BYTES_PER_TEXEL * (c * c) as f64) * 100.0;
            let paper = PAPER_EXPLICIT
                .iter()
                .find(|p| p.0 == c)
                .map(|p| format!("{:.2} % {}", PAPER_OURS_MB / p.1 * 100.0, p.2))
                .unwrap_or_default();
            println!(
                "{:<22} {:>5} {:>9.2} {:>9.2} {:>8.4} {:>9.2} {:>10} {:>11.1} {:>7.3}% {:>12.3}% {:>14}",
                label,
                patch,
                mb(*texels),
                mb(*table),
                mb(*gauss),
                mb(total),
                format!("{c}²"),
                mb(explicit),
                ratio,
                yan,
                paper
            );
            notes.push((
                format!("{label} against coverage {c}²: constant / explicit %"),
                ratio,
            ));
            notes.push((
                format!("{label} against coverage {c}² at Yan16 bytes per texel: %"),
                yan,
            ));
        }
    }
    for &c in coverage {
        notes.push((
            format!("coverage {c}²: explicit map bytes"),
            explicit_bytes(c) as f64,
        ));
    }
    for (c, explicit_mb, scene) in PAPER_EXPLICIT {
        notes.push((
            format!(
                "paper {scene}: 512² example {PAPER_OURS_MB} MB / {c}² explicit {explicit_mb} MB %"
            ),
            PAPER_OURS_MB / explicit_mb * 100.0,
        ));
        notes.push((
            format!("paper {scene}: explicit bytes per texel"),
            explicit_mb * 1e6 / (c * c) as f64,
        ));
    }
    println!(
        "paper (Table 1): 35.0 MB for a 512² example against 7,896.0 MB for the Chair's 5K² \
         map (0.44 %, about {:.0} bytes per texel: Yan et al. 2016 store Gaussian elements and \
         their hierarchy) and 1,119.9 MB for the Kettle's 2K² map (3.1 %)",
        YAN16_BYTES_PER_TEXEL
    );
}

/// The render part's scene at the asked size and samples, refused before anything is measured
/// when it has no glint material.
fn render_scene(args: &GlintsArgs) -> anyhow::Result<Scene> {
    let (res, spp) = if args.quick {
        (
            Resolution {
                width: 64,
                height: 48,
            },
            2,
        )
    } else {
        (args.render_res, args.spp)
    };
    res.check("--render-res", 1..=4096)?;
    ensure!(
        (1..=4096).contains(&spp),
        "--spp {spp}: must lie in 1..=4096"
    );
    let mut scene = Scene::load(&args.scene)?;
    ensure!(
        scene
            .materials
            .iter()
            .any(|m| m.kind == MaterialKind::Glint),
        "--scene {}: has no kind = \"glint\" material to measure",
        args.scene.display()
    );
    scene.render.width = res.width;
    scene.render.height = res.height;
    scene.render.spp = spp;
    Ok(scene)
}

/// The glint material's render time: the scene with its glints evaluated by the pruned
/// traversal, by the explicit reference (every texel of each footprint), and replaced by the
/// plain conductor they are made of. Each run builds the path tracer anew and times its
/// passes only (the device work of tracing and shading, not the scene's preparation).
fn render_part(
    bench: &mut Bench,
    gpu: &lazysolid_compute::gpu::Gpu,
    scene: &Scene,
    args: &GlintsArgs,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let r = &scene.render;
    let name = args
        .scene
        .file_name()
        .map_or_else(|| "scene".into(), |n| n.to_string_lossy().into_owned());
    let case = format!("render {name} {}×{} {} spp", r.width, r.height, r.spp);
    let samples = u64::from(r.width) * u64::from(r.height) * u64::from(r.spp);
    let mut mins = Vec::new();
    for c in GlintCase::ALL {
        bench.status(format!("{case}: {}", c.name()));
        let s = c.apply(scene);
        let baseline = match c {
            GlintCase::Pruned => Some(GlintCase::Explicit.name()),
            _ => None,
        };
        let min = bench.case(
            &case,
            samples,
            c.name(),
            Throughput::Items("sample"),
            baseline,
            || {
                let mut tracer = PathTracer::new(gpu, &s)?;
                let mut time = Duration::ZERO;
                tracer.render(|p| time += p.time)?;
                Ok(time.as_secs_f64() * 1e3)
            },
        )?;
        mins.push((c, min));
    }
    let ms = |case: GlintCase| mins.iter().find(|m| m.0 == case).map_or(f64::NAN, |m| m.1);
    let pruned = ms(GlintCase::Pruned);
    let explicit = ms(GlintCase::Explicit);
    let conductor = ms(GlintCase::ALL[2]);
    let over_explicit = (pruned / explicit - 1.0) * 100.0;
    let over_conductor = pruned / conductor;
    println!(
        "render ({case}, min of {} runs): conductor {conductor:.0} ms, glint explicit \
         {explicit:.0} ms, glint pruned {pruned:.0} ms: {over_explicit:+.0} % against the \
         explicit reference (paper: +3 % to +53 % against Yan et al. 2016), {over_conductor:.1}× \
         the conductor",
        bench
            .rows()
            .last()
            .map_or(0, |row| row.stats.samples_ms.len())
    );
    notes.push((format!("{case}: pruned over explicit %"), over_explicit));
    notes.push((format!("{case}: pruned / conductor"), over_conductor));
    Ok(())
}
