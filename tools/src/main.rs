//! `lazysolid`: the command-line front end of lazysolid.

// clap turns the arguments' doc comments into `--help` text, where `[render]` and
// `[[exemplar]]` are TOML tables, not links.
#![allow(rustdoc::broken_intra_doc_links)]

mod bench;
mod cli;

/// Counts heap bytes so `bench cuts` can report a cut's host temporary memory as measured.
#[global_allocator]
static ALLOCATOR: lazysolid_compute::host_memory::CountingAllocator =
    lazysolid_compute::host_memory::CountingAllocator;

use clap::{Parser, Subcommand};
use cli::exit_status;

/// GPU sparse texture structures, lazy solid texture synthesis and a path tracer, in explicit
/// Vulkan compute.
///
/// The same words mean the same things in every subcommand: --res WxH is the pixels of an image
/// (N alone is NxN), --voxel-res N the side of an N³ voxel grid, --mesh and --exemplar(s) take
/// an asset name (armadillo, leather; found in the repository's assets/ from any folder, or in
/// LAZYSOLID_ASSETS) or a path, -o/--output is a file to write and --out-dir a folder of
/// results, --builder where a perfect hash is constructed.
#[derive(Parser)]
#[command(
    name = "lazysolid",
    version = concat!(env!("CARGO_PKG_VERSION"), " (revision ", env!("LAZYSOLID_REVISION"), ")"),
    about,
    after_help = exit_status::HELP
)]
struct Cli {
    /// Vulkan device: a case-insensitive part of its name, or its index from `lazysolid device`.
    /// Defaults to a real GPU when one is present, else lavapipe.
    #[arg(long, global = true, env = "LAZYSOLID_DEVICE")]
    device: Option<String>,

    /// Print the chosen device and progress details.
    #[arg(long, short, global = true)]
    verbose: bool,

    /// Load the Khronos validation layer, as LAZYSOLID_VALIDATION=1 does: every error is
    /// printed at exit and makes the exit status 2.
    #[arg(long, global = true)]
    validation: bool,

    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the Vulkan devices with the limits and features lazysolid relies on.
    Device,
    /// Run a benchmark suite; tables go to stdout, CSV and JSON to the results folder.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// Compare an image with a reference using FLIP: statistics, an optional error map, and
    /// exit status 3 above an optional mean-error threshold.
    Diff(cli::diff::DiffArgs),
    /// Cut a closed mesh by planes or break it into Voronoi pieces, written as OBJ with the cut
    /// faces in their own group and material.
    Fracture(cli::fracture::FractureArgs),
    /// Path-trace a scene file (TOML) into a PNG and an HDR EXR.
    Render(cli::render::RenderArgs),
    /// Synthesize a window of the unbounded texture plane from an exemplar (PNG, JPEG or GIMP
    /// .pat) into a PNG and its exemplar-coordinate map, with timings and quality metrics.
    Synth(cli::synth::SynthArgs),
    /// Synthesize a window of any depth of the multiscale texture an exemplar graph (TOML)
    /// defines, into a PNG and a map of the exemplar each pixel uses.
    Multiscale(cli::multiscale::MultiscaleArgs),
    /// Zoom into a point of an exemplar graph's multiscale texture: numbered PNG frames at
    /// fractional depths and an animated GIF.
    Zoom(cli::multiscale::ZoomArgs),
    /// Synthesize a cube of the unbounded solid texture from 2D exemplars into NRRD, with
    /// slices, the candidate slab, timings and per-axis quality.
    Solid(cli::solid::SolidArgs),
}

fn main() {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // Usage errors exit with 1 like every other error (clap's own 2 is validation's).
            let _ = e.print();
            if let Some(clap::error::ContextValue::String(flag)) =
                e.get(clap::error::ContextKind::InvalidArg)
            {
                let args: Vec<String> = std::env::args().skip(1).collect();
                if let Some(line) = cli::renamed::hint(&args, flag) {
                    eprintln!("{line}");
                }
            }
            std::process::exit(if e.use_stderr() {
                exit_status::ERROR
            } else {
                exit_status::SUCCESS
            });
        }
    };
    env_logger::Builder::from_env(
        env_logger::Env::default().default_filter_or(if cli.verbose { "info" } else { "warn" }),
    )
    .init();
    let global = cli::GlobalArgs {
        device: cli.device.clone(),
        verbose: cli.verbose,
        validation: cli.validation,
        validation_logs: Default::default(),
    };
    let result = match cli.command {
        Command::Device => cli::device::run(cli.device.as_deref()),
        Command::Bench(b) => bench::run(b, &global),
        Command::Diff(d) => cli::diff::run(&d),
        Command::Render(r) => cli::render::run(&r, &global),
        Command::Synth(s) => cli::synth::run(&s, &global),
        Command::Multiscale(m) => cli::multiscale::run(&m, &global),
        Command::Zoom(z) => cli::multiscale::run_zoom(&z, &global),
        Command::Fracture(f) => cli::fracture::run(&f, &global),
        Command::Solid(s) => cli::solid::run(&s, &global),
    };
    // Every device is dropped by now, so leak reports are in the logs.
    let validation_errors = global.report_validation();
    if let Err(e) = result {
        if let Some(above) = e.downcast_ref::<cli::diff::AboveThreshold>() {
            eprintln!("{above}");
            std::process::exit(exit_status::ABOVE_THRESHOLD);
        }
        eprintln!("error: {e:#}");
        std::process::exit(exit_status::ERROR);
    }
    if validation_errors > 0 {
        std::process::exit(exit_status::VALIDATION);
    }
}
