//! `lazysolid diff`: how visibly a render differs from a reference, as FLIP statistics, an
//! optional error map, and an optional pass/fail threshold for scripts and CI.

use super::output::check_writable;
use anyhow::Context;
use clap::Args;
use lazysolid_renderer::diff::flip_files;
use std::path::PathBuf;

/// Arguments of `lazysolid diff`.
#[derive(Args)]
pub struct DiffArgs {
    /// The reference image (8-bit or 16-bit PNG or JPEG; alpha is ignored).
    pub reference: PathBuf,
    /// The image to judge against it, of the same size.
    pub test: PathBuf,
    /// Write the per-pixel FLIP error, colour-mapped with magma (black: none), as a PNG here.
    #[arg(long, value_name = "OUT.png")]
    pub error_map: Option<PathBuf>,
    /// Fail with exit status 3 (not 1, an error) when the mean FLIP error is above this value
    /// (0..1).
    #[arg(long, value_name = "T", value_parser = parse_threshold, allow_hyphen_values = true)]
    pub max_mean: Option<f32>,
}

fn parse_threshold(text: &str) -> Result<f32, String> {
    let t: f32 = text
        .parse()
        .map_err(|e| format!("{text:?} is not a number: {e}"))?;
    if (0.0..=1.0).contains(&t) {
        Ok(t)
    } else {
        Err(format!("{text} is outside 0..1, the range of FLIP errors"))
    }
}

/// A comparison that worked and found the images too different: exit status 3, told apart
/// from errors.
#[derive(Debug)]
pub struct AboveThreshold {
    pub mean: f32,
    pub limit: f32,
    pub reference: PathBuf,
    pub test: PathBuf,
}

impl std::fmt::Display for AboveThreshold {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "FLIP mean {:.6} is above --max-mean {}: {} differs visibly from {}",
            self.mean,
            self.limit,
            self.test.display(),
            self.reference.display()
        )
    }
}

impl std::error::Error for AboveThreshold {}

/// Compares, prints one statistic per line, writes the error map when asked, then applies the
/// threshold (after writing, so a failing comparison still leaves its map to look at).
pub fn run(args: &DiffArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.error_map {
        check_writable("--error-map", path).context("the error map cannot be written")?;
    }
    let report = flip_files(&args.reference, &args.test)?;
    println!("reference   {}", args.reference.display());
    println!("test        {}", args.test.display());
    println!(
        "size        {}x{} ({} pixels)",
        report.width,
        report.height,
        u64::from(report.width) * u64::from(report.height)
    );
    for (name, value) in [
        ("mean", report.mean),
        ("median", report.median),
        ("p95", report.p95),
        ("p99", report.p99),
        ("max", report.max),
    ] {
        println!("FLIP {name:<6} {value:.6}");
    }
    if let Some(path) = &args.error_map {
        report
            .write_error_map(path)
            .context("writing the FLIP error map")?;
        println!("error map   {}", path.display());
    }
    if let Some(limit) = args.max_mean {
        if report.mean > limit {
            return Err(AboveThreshold {
                mean: report.mean,
                limit,
                reference: args.reference.clone(),
                test: args.test.clone(),
            }
            .into());
        }
        println!("FLIP mean {:.6} is within --max-mean {limit}", report.mean);
    }
    Ok(())
}
