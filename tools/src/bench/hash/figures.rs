//! The figures of `bench hash`: rates versus load factor, the age histograms of Robin Hood and
//! plain open addressing (thesis Fig. 4.16), and the table contents and max-age maps of coherent
//! and random probing (Figs. 4.15 and 4.17).

use super::datasets::Dataset;
use super::Sweep;
use crate::bench::plot::{bar_chart, heat, line_chart, rgb_image, Series};
use lazysolid_compute::hash::{
    plain_open_addressing_ages, CellFormat, HashKernels, KeyLayout, Probe, RobinHoodConfig,
    RobinHoodTable,
};
use std::path::Path;
use std::sync::Arc;

pub(crate) fn draw(
    dir: &Path,
    kernels: &Arc<HashKernels>,
    random: Option<&Dataset>,
    sweeps: &[Sweep],
    pictures: &[(String, Vec<u64>, CellFormat, u32)],
) -> anyhow::Result<()> {
    for s in sweeps {
        for (op, file, title) in [
            ("insert", "insert-vs-load-factor", "insertion"),
            (
                "query sorted 100%",
                "query-vs-load-factor",
                "queries (present keys, sorted)",
            ),
            (
                "query shuffled 100%",
                "query-shuffled-vs-load-factor",
                "queries (present keys, shuffled)",
            ),
            (
                "query sorted 0%",
                "query-absent-vs-load-factor",
                "queries (absent keys, sorted)",
            ),
        ] {
            let mut series: Vec<Series> = ["coherent", "random", "cuckoo"]
                .iter()
                .map(|scheme| Series {
                    name: scheme.to_string(),
                    points: s
                        .rows
                        .iter()
                        .filter(|r| r.0 == *scheme && r.2 == op)
                        .map(|r| (r.1, r.3))
                        .collect(),
                })
                .filter(|s| !s.points.is_empty())
                .collect();
            if op == "query sorted 100%" {
                let lfs: Vec<f64> = s.rows.iter().filter(|r| r.2 == op).map(|r| r.1).collect();
                let (lo, hi) = lfs
                    .iter()
                    .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
                series.push(Series {
                    name: "dense array (gpu)".into(),
                    points: vec![(lo, s.dense_sorted), (hi, s.dense_sorted)],
                });
                series.push(Series {
                    name: "hashbrown (cpu, 2 threads)".into(),
                    points: vec![(lo, s.hashbrown_sorted), (hi, s.hashbrown_sorted)],
                });
            }
            line_chart(
                &dir.join(format!("{}-{file}.png", s.dataset)),
                &format!("{}: {title}", s.dataset),
                "load factor",
                "Mkeys/s",
                &series,
            )?;
        }
    }

    // Fig. 4.16: ages of random keys at load factor 0.8, plain open addressing vs Robin Hood.
    if let Some(random) = random {
        age_histogram(dir, kernels, random)?;
    }
    table_pictures(dir, pictures)
}

fn age_histogram(dir: &Path, kernels: &Arc<HashKernels>, random: &Dataset) -> anyhow::Result<()> {
    let u = random.universe(KeyLayout::RowMajor);
    let keys: Vec<u64> = random.points.iter().map(|&p| u.key(p)).collect();
    let size = ((keys.len() as f64 / 0.8).ceil() as u32) | 1;
    let plain = plain_open_addressing_ages(kernels, &keys, size, Probe::Random, 4096)?;
    let plain_max = plain.iter().copied().max().unwrap_or(1).max(1);
    let mut hist_plain = vec![0f64; plain_max as usize + 1];
    for a in plain {
        hist_plain[a as usize] += 1.0;
    }
    let mut series = vec![(
        "plain open addressing, random probe".to_string(),
        hist_plain[1..].to_vec(),
    )];
    for probe in [Probe::Random, Probe::Coherent] {
        let config = RobinHoodConfig {
            probe,
            load_factor: 0.8,
            histogram: true,
            grow: false,
            validate: false,
            ..Default::default()
        };
        let t = RobinHoodTable::build_from_slices(kernels, u, &keys, &random.payloads, config)?;
        let h = t.report.age_histogram.clone().unwrap_or_default();
        let mut v = vec![0f64; plain_max as usize];
        for (age, count) in h.iter().enumerate().skip(1) {
            if age <= v.len() {
                v[age - 1] = *count as f64;
            }
        }
        series.push((format!("Robin Hood, {} probe", probe.name()), v));
    }
    let categories: Vec<String> = (1..=plain_max).map(|a| a.to_string()).collect();
    bar_chart(
        &dir.join("age-histogram.png"),
        &format!(
            "ages of {} random keys at load factor 0.8 (max: plain {plain_max})",
            keys.len()
        ),
        "age (probe steps)",
        "keys",
        &categories,
        &series,
        true,
    )?;
    Ok(())
}

/// Figs. 4.15 and 4.17: table contents and max-age maps, one table row per image row.
fn table_pictures(
    dir: &Path,
    pictures: &[(String, Vec<u64>, CellFormat, u32)],
) -> anyhow::Result<()> {
    for (name, cells, format, width) in pictures {
        let w = *width;
        let h = (cells.len() as u32).div_ceil(w);
        let mut contents = vec![0u8; (w * h * 3) as usize];
        let mut ages = vec![0u8; (w * h * 3) as usize];
        for (i, &c) in cells.iter().enumerate() {
            if c == 0 {
                continue;
            }
            let p = format.payload(c);
            contents[3 * i..3 * i + 3].copy_from_slice(&[(p >> 16) as u8, (p >> 8) as u8, p as u8]);
            ages[3 * i..3 * i + 3].copy_from_slice(&heat(format.age(c) as f64 / 15.0));
        }
        rgb_image(
            &dir.join(format!("table-contents-{name}.png")),
            w,
            h,
            contents,
        )?;
        rgb_image(&dir.join(format!("max-age-map-{name}.png")), w, h, ages)?;
    }
    Ok(())
}
