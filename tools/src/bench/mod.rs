//! `lazysolid bench …`: benchmark suites sharing one harness (warm-up, repeated runs, min and
//! median, ratios against a baseline measured in the same run, table + CSV + JSON).

mod correction_profile;
mod ctree;
mod cuts;
mod glints;
pub mod harness;
mod hash;
mod lazy;
mod multiscale;
mod normalmaps;
mod plot;
mod prims;
mod psh;
mod solid;
mod synth;
mod textures;
mod trace;

use crate::cli::output::check_writable_dir;
use crate::cli::GlobalArgs;
use clap::{Args, Subcommand};
use std::path::PathBuf;

/// Benchmark suites.
#[derive(Subcommand)]
pub enum BenchCommand {
    /// Scan, reduce, compaction and radix sort against their CPU references and a copy kernel.
    Prims(prims::PrimsArgs),
    /// Coherent, random-probe and cuckoo hashing against a dense array and CPU hashbrown.
    Hash(hash::HashArgs),
    /// Perfect spatial hashing: offset-table bits per key, bytes, CPU versus GPU construction,
    /// queries next to the coherent hash and a dense array.
    Psh(psh::PshArgs),
    /// GLSL CWBVH ray traversal against obvhs's CPU traversal of the same rays, BVH builds.
    Trace(trace::TraceArgs),
    /// GPU appearance-space synthesis against the texture-synthesis crate: time and quality.
    Synth(synth::SynthArgs),
    /// Multiscale synthesis from exemplar graphs: throughput against the single-exemplar
    /// synthesizer, analysis time, per-depth energy and repetition.
    Multiscale(multiscale::MultiscaleBenchArgs),
    /// Solid synthesis from 2D exemplars: candidate and synthesis times, per-axis quality
    /// beside the 2D synthesizer and two ablations.
    Solid(solid::SolidArgs),
    /// Lazy solid synthesis around mesh surfaces: voxels synthesized per level, time, kept
    /// state, against the full volume and the thesis.
    Lazy(lazy::LazyArgs),
    /// New surface on demand: per plane cut and per Voronoi fracture of a mesh, the voxels
    /// its caps need, their synthesis and insert time, state and store growth.
    Cuts(cuts::CutsArgs),
    /// Glints by example: range min/max queries of the sparse table against a min–max mip
    /// and brute force (bytes, build, query rate), and the constant storage against the
    /// explicit method's materialized map (`--part`).
    Glints(glints::GlintsArgs),
    /// Normal maps from near to far (seed 000 ch. 7): unfiltered, plain MIP and vMF filtering
    /// against a many-sample reference (FLIP, far-field error), and the vMF fit's time and
    /// memory per map size.
    Normalmaps(normalmaps::NormalMapsArgs),
    /// Compressed random-access trees (thesis §4.1.3): rate–distortion against BC1, BC4, BC7
    /// and 2×2 VQ, Table 4.2 and topology bytes per node, device against host builds, lookups
    /// against the sparse stores and a plain MIP texture.
    Ctree(ctree::CtreeArgs),
    /// Thesis Table 4.1: memory and lookup speed of every sparse texture structure over a mesh
    /// at one equivalent resolution, seen from a fixed 800×800 viewpoint, with pictures.
    Textures(textures::TexturesArgs),
}

/// Options every suite shares.
#[derive(Args, Clone)]
pub struct CommonArgs {
    /// Unmeasured runs before the measured ones (lavapipe compiles kernels at first dispatch).
    #[arg(long, default_value_t = 2)]
    pub warmup: usize,
    /// Measured runs per case; the table reports their min and median.
    #[arg(long, default_value_t = 5)]
    pub runs: usize,
    /// Folder for the CSV and JSON files and the figures (created if needed, checked before
    /// the suite starts).
    #[arg(long, value_name = "DIR", default_value = "results")]
    pub out_dir: PathBuf,
}

/// Runs the chosen suite.
pub fn run(command: BenchCommand, global: &GlobalArgs) -> anyhow::Result<()> {
    let common = match &command {
        BenchCommand::Prims(a) => &a.common,
        BenchCommand::Hash(a) => &a.common,
        BenchCommand::Psh(a) => &a.common,
        BenchCommand::Trace(a) => &a.common,
        BenchCommand::Synth(a) => &a.common,
        BenchCommand::Multiscale(a) => &a.common,
        BenchCommand::Solid(a) => &a.common,
        BenchCommand::Lazy(a) => &a.common,
        BenchCommand::Cuts(a) => &a.common,
        BenchCommand::Glints(a) => &a.common,
        BenchCommand::Textures(a) => &a.common,
        BenchCommand::Normalmaps(a) => &a.common,
        BenchCommand::Ctree(a) => &a.common,
    };
    check_writable_dir("--out-dir", &common.out_dir)?;
    match command {
        BenchCommand::Prims(args) => prims::run(&args, global),
        BenchCommand::Hash(args) => hash::run(&args, global),
        BenchCommand::Psh(args) => psh::run(&args, global),
        BenchCommand::Trace(args) => trace::run(&args, global),
        BenchCommand::Synth(args) => synth::run(&args, global),
        BenchCommand::Multiscale(args) => multiscale::run(&args, global),
        BenchCommand::Solid(args) => solid::run(&args, global),
        BenchCommand::Lazy(args) => lazy::run(&args, global),
        BenchCommand::Cuts(args) => cuts::run(&args, global),
        BenchCommand::Glints(args) => glints::run(&args, global),
        BenchCommand::Textures(args) => textures::run(&args, global),
        BenchCommand::Normalmaps(args) => normalmaps::run(&args, global),
        BenchCommand::Ctree(args) => ctree::run(&args, global),
    }
}
