//! Parameter sweep of the 2D synthesizer: mean neighbourhood energy, histogram distance and
//! period repetition of several parameter variants over several seeds and exemplars, with one
//! picture per variant (how the defaults in docs/synthesis.md were chosen).
//!
//! ```text
//! cargo run -p lazysolid-tools --example synth_sweep -- OUT_DIR SIZE SEEDS EXEMPLAR,... VARIANT...
//! ```
//! `SEEDS` is `FIRST..=LAST`. A variant is `NAME` (the defaults) or `NAME:FIELD=VALUE;...` with
//! fields `jitter` (strengths coarsest first, the last one repeated to the finest level),
//! `passes` (counts coarsest first; the last applies to the finest level, the one before it
//! to every level between), `spread`, `k` and `penalty` (the period penalty). Exemplars are
//! paths or names in assets/exemplars. The analysis goes through the user's analysis cache.

use anyhow::{bail, Context};
use lazysolid_compute::gpu::{Gpu, GpuOptions};
use lazysolid_synth::{
    analyze_cached, default_jitter, default_passes, histogram_distance, period_repetition,
    AnalysisParams, DiskCache, EnergyKernel, EnergyReport, Exemplar, GpuSynthesizer, Region,
    SynthParams, DEFAULT_PERIOD_PENALTY,
};
use std::path::{Path, PathBuf};

struct Variant {
    name: String,
    jitter: Option<Vec<f32>>,
    passes: Option<Vec<u32>>,
    analysis: AnalysisParams,
    penalty: u32,
}

fn parse_variant(s: &str) -> anyhow::Result<Variant> {
    let (name, fields) = s.split_once(':').unwrap_or((s, ""));
    let mut v = Variant {
        name: name.to_string(),
        jitter: None,
        passes: None,
        analysis: AnalysisParams::default(),
        penalty: DEFAULT_PERIOD_PENALTY,
    };
    for field in fields.split(';').filter(|f| !f.is_empty()) {
        let (key, value) = field
            .split_once('=')
            .with_context(|| format!("{field:?} is not FIELD=VALUE"))?;
        let list = |value: &str| -> anyhow::Result<Vec<f64>> {
            value
                .split(',')
                .map(|x| x.parse().with_context(|| format!("{x:?} in {field:?}")))
                .collect()
        };
        match key {
            "jitter" => v.jitter = Some(list(value)?.into_iter().map(|x| x as f32).collect()),
            "passes" => v.passes = Some(list(value)?.into_iter().map(|x| x as u32).collect()),
            "spread" => v.analysis.spread = value.parse()?,
            "k" => v.analysis.k = value.parse()?,
            "penalty" => v.penalty = value.parse()?,
            _ => bail!("unknown field {key:?} in variant {s:?}"),
        }
    }
    Ok(v)
}

/// The variant's per-level lists for a pyramid of `levels` levels.
fn schedule(v: &Variant, levels: u32) -> (Vec<u32>, Vec<f32>) {
    let n = levels as usize;
    let passes = match &v.passes {
        None => default_passes(levels),
        Some(p) if p.len() == 1 => vec![p[0]; n],
        Some(p) => (0..n)
            .map(|l| {
                if l + 1 == n {
                    p[p.len() - 1]
                } else {
                    p[l.min(p.len() - 2)]
                }
            })
            .collect(),
    };
    let jitter = match &v.jitter {
        None => default_jitter(levels),
        Some(j) => (0..n).map(|l| j[l.min(j.len() - 1)]).collect(),
    };
    (passes, jitter)
}

fn exemplar_path(name: &str) -> PathBuf {
    if name.contains('/') || name.contains('.') {
        PathBuf::from(name)
    } else {
        Path::new("assets/exemplars").join(format!("{name}.pat"))
    }
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 5 {
        bail!("usage: synth_sweep OUT_DIR SIZE FIRST..=LAST EXEMPLAR,... VARIANT...");
    }
    let out = PathBuf::from(&args[0]);
    std::fs::create_dir_all(&out)?;
    let size: u32 = args[1].parse()?;
    let (first, last) = args[2].split_once("..=").context("SEEDS is FIRST..=LAST")?;
    let seeds: Vec<u32> = (first.parse()?..=last.parse()?).collect();
    let variants = args[4..]
        .iter()
        .map(|s| parse_variant(s))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let gpu = Gpu::new(&GpuOptions::from_env())?;
    let energy = EnergyKernel::new(&gpu)?;
    let cache = DiskCache::user()?;
    let window = Region {
        origin: [0, 0],
        size: [size, size],
    };
    println!(
        "{:<14} {:<18} {:>8} {:>8} {:>7} {:>7} {:>7}  repetition per seed",
        "exemplar", "variant", "energy", "low-rep", "hist", "rep", "max rep"
    );
    for name in args[3].split(',') {
        let exemplar = Exemplar::load(&exemplar_path(name))?;
        for v in &variants {
            let (analysis, _) = analyze_cached(&exemplar, &v.analysis, Some(&cache))?;
            let levels = analysis.levels.len() as u32;
            let (passes, jitter) = schedule(v, levels);
            let synth = GpuSynthesizer::new(&gpu, &analysis)?;
            let (mut energies, mut hists, mut reps) = (vec![], vec![], vec![]);
            for &seed in &seeds {
                let params = SynthParams::new(levels, seed, &passes, &jitter)?
                    .with_period_penalty(v.penalty)?;
                let s = synth.synthesize(&analysis, &params, window, false, &mut |_| {})?;
                let colours = s.colours(&exemplar);
                let minima = energy.minima(&exemplar, &colours, size, size, 4096)?;
                energies.push(EnergyReport::from_minima(&minima).mean);
                hists.push(histogram_distance(&exemplar.rgb, &colours));
                reps.push(period_repetition(
                    &s.window_coords(),
                    size,
                    size,
                    exemplar.width,
                    exemplar.height,
                ));
                if seed == seeds[0] {
                    let bytes: Vec<u8> = colours.iter().flatten().copied().collect();
                    image::save_buffer(
                        out.join(format!("{name}-{}-{size}.png", v.name)),
                        &bytes,
                        size,
                        size,
                        image::ExtendedColorType::Rgb8,
                    )?;
                }
            }
            let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
            let low: Vec<f64> = energies
                .iter()
                .zip(&reps)
                .filter(|(_, &r)| r <= 0.35)
                .map(|(&e, _)| e)
                .collect();
            println!(
                "{:<14} {:<18} {:>8.0} {:>8} {:>7.4} {:>7.3} {:>7.3}  {}",
                name,
                v.name,
                mean(&energies),
                if low.is_empty() {
                    "-".to_string()
                } else {
                    format!("{:.0}", mean(&low))
                },
                mean(&hists),
                mean(&reps),
                reps.iter().copied().fold(0.0, f64::max),
                reps.iter()
                    .map(|r| format!("{r:.2}"))
                    .collect::<Vec<_>>()
                    .join(" ")
            );
        }
    }
    Ok(())
}
