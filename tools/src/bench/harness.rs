//! The benchmark harness every `bench` suite uses.
//!
//! A case is timed `warmup + runs` times; only the last `runs` count. GPU cases report the
//! timestamp-query time of the recorded work, CPU cases wall time. Every row may name a
//! baseline row of the same run; its ratio is `baseline min / this min` (above 1: faster).

use super::CommonArgs;
use crate::cli::output::write_atomically;
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use lazysolid_compute::gpu::{Gpu, GpuResult, Recorder};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// The project's revision this executable was built from (`tools/build.rs`): `unknown`
/// outside a git checkout, `-dirty` when tracked files differed from the commit.
pub const REVISION: &str = env!("LAZYSOLID_REVISION");

/// Facts that make a result file interpretable later: where, when and on what it was run.
#[derive(Clone, Debug, Serialize)]
pub struct RunInfo {
    pub suite: String,
    pub device: String,
    pub device_type: String,
    pub driver: String,
    pub vulkan_api: String,
    /// `auto` or `device-local` (`LAZYSOLID_MEMORY`): whether uploads and readbacks were
    /// mapped copies or went through staging, which changes what the wall times include.
    pub memory_mode: String,
    /// When the run started: the one timestamp of the run, also in its file and folder names.
    pub date_utc: String,
    /// The project's revision the executable was built from.
    pub revision: String,
    pub host_cpu: String,
    pub host_threads: usize,
    pub warmup: usize,
    pub runs: usize,
    pub command_line: String,
}

/// Min, median and mean of the measured runs, in milliseconds.
#[derive(Clone, Debug, Serialize)]
pub struct Stats {
    pub min_ms: f64,
    pub median_ms: f64,
    pub mean_ms: f64,
    pub samples_ms: Vec<f64>,
}

impl Stats {
    fn from_samples(mut samples: Vec<f64>) -> Stats {
        let raw = samples.clone();
        samples.sort_by(f64::total_cmp);
        let n = samples.len();
        let median = if n % 2 == 1 {
            samples[n / 2]
        } else {
            0.5 * (samples[n / 2 - 1] + samples[n / 2])
        };
        Stats {
            min_ms: samples[0],
            median_ms: median,
            mean_ms: samples.iter().sum::<f64>() / n as f64,
            samples_ms: raw,
        }
    }
}

/// One measured case.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The operation, e.g. `radix sort u32`.
    pub case: String,
    /// Elements processed.
    pub elements: u64,
    /// Who ran it, e.g. `gpu` or `cpu std sort_unstable (1 thread)`.
    pub implementation: String,
    /// Where the measured structure was constructed, where that is a choice (`--builder`):
    /// `cpu` or `gpu` for perfect hashes, none otherwise.
    pub builder: Option<String>,
    pub stats: Stats,
    /// Throughput at the min time.
    pub throughput: f64,
    pub throughput_unit: String,
    /// The row this one is compared with, and `baseline min / this min`.
    pub baseline: Option<String>,
    pub ratio: Option<f64>,
}

/// Collects rows for one suite and writes them out.
pub struct Bench {
    pub info: RunInfo,
    stamp: String,
    rows: Vec<Row>,
    out: PathBuf,
    progress: ProgressBar,
}

/// How a case's throughput is expressed.
#[derive(Clone, Copy)]
pub enum Throughput {
    /// Million elements per second.
    Elements,
    /// Gigabytes per second for this many bytes moved per run.
    Bytes(u64),
    /// Millions of the named items per second (e.g. `query` gives Mquery/s).
    Items(&'static str),
}

impl Bench {
    /// Starts a suite of `cases` cases on `gpu`.
    pub fn new(suite: &str, gpu: &Gpu, common: &CommonArgs, cases: u64) -> anyhow::Result<Bench> {
        anyhow::ensure!(common.runs >= 1, "--runs must be at least 1");
        let start = chrono::Utc::now();
        let d = gpu.info();
        let info = RunInfo {
            suite: suite.to_string(),
            device: d.name.clone(),
            device_type: d.device_type.clone(),
            driver: d.driver.clone(),
            vulkan_api: d.api_version.clone(),
            memory_mode: gpu.memory_mode().name().to_string(),
            date_utc: start.format("%Y-%m-%dT%H:%M:%SZ").to_string(),
            revision: REVISION.to_string(),
            host_cpu: host_cpu(),
            host_threads: std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1),
            warmup: common.warmup,
            runs: common.runs,
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
        };
        let progress = ProgressBar::new(cases);
        progress.set_style(
            ProgressStyle::with_template(
                "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {msg}",
            )
            .unwrap(),
        );
        Ok(Bench {
            stamp: start.format("%Y%m%d-%H%M%S").to_string(),
            info,
            rows: Vec::new(),
            out: common.out_dir.clone(),
            progress,
        })
    }

    /// Times `run` (which returns the time of one run in ms) with warm-up, records the row and
    /// returns its min time. `baseline` names the implementation of the same case this row is
    /// compared with: ratio = baseline min / this min, above 1 when this row is faster.
    pub fn case(
        &mut self,
        case: &str,
        elements: u64,
        implementation: &str,
        throughput: Throughput,
        baseline: Option<&str>,
        mut run: impl FnMut() -> anyhow::Result<f64>,
    ) -> anyhow::Result<f64> {
        self.progress
            .set_message(format!("{case} — {implementation}"));
        for _ in 0..self.info.warmup {
            run().with_context(|| format!("{case} ({implementation}), warm-up"))?;
        }
        let mut samples = Vec::with_capacity(self.info.runs);
        for _ in 0..self.info.runs {
            samples.push(run().with_context(|| format!("{case} ({implementation})"))?);
        }
        let stats = Stats::from_samples(samples);
        let (throughput, unit) = match throughput {
            Throughput::Elements => (
                elements as f64 / (stats.min_ms * 1e-3) / 1e6,
                "Melem/s".to_string(),
            ),
            Throughput::Bytes(b) => (b as f64 / (stats.min_ms * 1e-3) / 1e9, "GB/s".into()),
            Throughput::Items(item) => (
                elements as f64 / (stats.min_ms * 1e-3) / 1e6,
                format!("M{item}/s"),
            ),
        };
        let min = stats.min_ms;
        self.rows.push(Row {
            case: case.into(),
            elements,
            implementation: implementation.into(),
            builder: None,
            stats,
            throughput,
            throughput_unit: unit,
            baseline: baseline.map(str::to_string),
            ratio: None,
        });
        self.resolve_ratios();
        self.progress.inc(1);
        Ok(min)
    }

    /// Records where the structure the last row measured was constructed (`cpu` or `gpu`).
    pub fn set_builder(&mut self, builder: &str) {
        if let Some(row) = self.rows.last_mut() {
            row.builder = Some(builder.to_string());
        }
    }

    /// Shows what the suite is doing between timed cases (untimed work such as scoring).
    pub fn status(&self, message: String) {
        self.progress.set_message(message);
    }

    /// `<out>/<suite>-<date>/`, created on first use: where a suite puts its figures.
    pub fn artifact_dir(&self) -> anyhow::Result<PathBuf> {
        let dir = self.artifact_path();
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        Ok(dir)
    }

    /// `<out>/<suite>-<date>`: the stem of every file and folder of the run.
    fn artifact_path(&self) -> PathBuf {
        self.out.join(format!(
            "{}-{}",
            self.info.suite.replace(' ', "-"),
            self.stamp
        ))
    }

    /// Rows so far; a row's ratio is set once its baseline row exists (in either order).
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    fn resolve_ratios(&mut self) {
        for i in 0..self.rows.len() {
            let r = &self.rows[i];
            let base = r.baseline.as_ref().and_then(|b| {
                self.rows
                    .iter()
                    .find(|o| o.case == r.case && &o.implementation == b)
            });
            let ratio = base.map(|b| b.stats.min_ms / r.stats.min_ms);
            self.rows[i].ratio = ratio;
        }
    }

    /// Prints the table, writes `<out>/<suite>-<date>.csv` and `.json` and says where they and
    /// the suite's figures (if it made any) are; returns the two paths.
    pub fn finish(self, notes: &[(String, f64)]) -> anyhow::Result<(PathBuf, PathBuf)> {
        self.progress.finish_and_clear();
        let i = &self.info;
        println!(
            "{} on {} ({}), {}, revision {}, {} warm-up + {} runs",
            i.suite, i.device, i.driver, i.date_utc, i.revision, i.warmup, i.runs
        );
        println!(
            "{:<28} {:>11} {:<36} {:>10} {:>10} {:>12} {:>9}",
            "case", "elements", "implementation", "min ms", "median ms", "throughput", "ratio"
        );
        for r in &self.rows {
            let ratio = r.ratio.map(|x| format!("{x:.2}x")).unwrap_or_default();
            let implementation = match &r.builder {
                Some(b) => format!("{} [{b}-built]", r.implementation),
                None => r.implementation.clone(),
            };
            println!(
                "{:<28} {:>11} {:<36} {:>10.3} {:>10.3} {:>7.1} {:<8} {:>8}",
                r.case,
                r.elements,
                implementation,
                r.stats.min_ms,
                r.stats.median_ms,
                r.throughput,
                r.throughput_unit,
                ratio
            );
        }
        for (name, value) in notes {
            println!("{name}: {value:.3}");
        }
        std::fs::create_dir_all(&self.out)
            .with_context(|| format!("creating {}", self.out.display()))?;
        let base = self.artifact_path();
        let csv = base.with_extension("csv");
        let json = base.with_extension("json");
        write_atomically(&csv, |f| self.write_csv(f))?;
        let notes: serde_json::Map<String, serde_json::Value> = notes
            .iter()
            .map(|(k, v)| (k.clone(), serde_json::json!(v)))
            .collect();
        write_atomically(&json, |f| {
            Ok(serde_json::to_writer_pretty(
                f,
                &serde_json::json!({ "run": i, "rows": self.rows, "derived": notes }),
            )?)
        })?;
        println!("results: {} and {}", csv.display(), json.display());
        let figures = self.artifact_path();
        if figures.is_dir() {
            println!("figures: {}", figures.display());
        }
        Ok((csv, json))
    }

    /// One header line, then one row per case; every row repeats the run's suite, date,
    /// revision and device so that files of several runs concatenate into one table. Fields
    /// are quoted where they hold commas or quotes.
    fn write_csv(&self, out: &mut impl std::io::Write) -> anyhow::Result<()> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record([
            "suite",
            "date_utc",
            "revision",
            "device",
            "case",
            "elements",
            "implementation",
            "builder",
            "min_ms",
            "median_ms",
            "mean_ms",
            "throughput",
            "throughput_unit",
            "baseline",
            "ratio",
        ])?;
        let i = &self.info;
        for r in &self.rows {
            w.write_record([
                i.suite.clone(),
                i.date_utc.clone(),
                i.revision.clone(),
                i.device.clone(),
                r.case.clone(),
                r.elements.to_string(),
                r.implementation.clone(),
                r.builder.clone().unwrap_or_default(),
                format!("{:.6}", r.stats.min_ms),
                format!("{:.6}", r.stats.median_ms),
                format!("{:.6}", r.stats.mean_ms),
                format!("{:.4}", r.throughput),
                r.throughput_unit.clone(),
                r.baseline.clone().unwrap_or_default(),
                r.ratio.map(|x| format!("{x:.4}")).unwrap_or_default(),
            ])?;
        }
        w.flush()?;
        Ok(())
    }
}

/// The device time of the commands `work` records, in milliseconds, from two GPU timestamps
/// around them (no submission, waiting or read-back in the time).
pub fn time_gpu(
    gpu: &Gpu,
    work: impl FnOnce(&mut Recorder<'_>) -> GpuResult<()>,
) -> anyhow::Result<f64> {
    let ((), t) = gpu.submit_timed(|rec| {
        rec.timestamp()?;
        work(rec)?;
        rec.timestamp()
    })?;
    Ok((t[1] - t[0]) * 1e-6)
}

/// Times a CPU closure in milliseconds.
pub fn time_cpu<R>(f: impl FnOnce() -> R) -> (R, f64) {
    let t = Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64() * 1e3)
}

fn host_cpu() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}
