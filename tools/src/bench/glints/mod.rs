//! `lazysolid bench glints`: the glint microstructure by example: its range-query structure,
//! its memory and its material's render time. The suite has parts, chosen with `--part`, that
//! join one table, one module each:
//!
//! - `structures`: range min/max queries over the example, per example size n (target patch
//!   l = n / 4): the square-only sparse table against a min–max mip hierarchy and brute force,
//!   their bytes, build time and query rate, all answers identical.
//! - `render`: the glint material's render time on a scene (`scenes/glints.toml`) against the
//!   explicit reference and the plain conductor.
//! - `memory`: the constant storage of the method against the materialized normal map the
//!   explicit method needs, beside the paper's Table 1.
//!
//! This module holds the arguments and runs the parts over the examples of `example`: an image
//! (the assets' exemplars or a path) read as a height map, cropped to N² where it is at least
//! that large, or a deterministic generated height field where it is not.

mod example;
mod memory;
mod render;
mod structures;

use super::harness::Bench;
use super::CommonArgs;
use crate::cli::assets::ExemplarDir;
use crate::cli::resolution::Resolution;
use crate::cli::GlobalArgs;
use anyhow::ensure;
use clap::{Args, ValueEnum};
use example::{example_of, load_image, short_source};
use lazysolid_renderer::glint::{GaussianTables, GlintCase};
use memory::memory_part;
use render::{render_part, render_scene};
use std::path::PathBuf;
use structures::{figures, measure_structures, print_structures};

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
    #[command(flatten)]
    pub exemplar_dir: ExemplarDir,
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

/// Runs the suite.
pub fn run(args: &GlintsArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
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
