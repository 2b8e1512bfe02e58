//! The structures part: range min/max queries over the example, per example size n (target
//! patch l = n / 4): the square-only sparse table (one lookup) against a min–max mip hierarchy
//! (the union of the square's maximal aligned blocks) and brute force (every texel of the
//! square). Bytes, build time (CPU, one thread, against the device's dispatches by GPU
//! timestamps; uploads excluded) and query rate (CPU, one thread, and GPU timestamps) over one
//! batch of random squares (random levels 0..=log2 l and starts, fixed seed). All six answer
//! vectors must be identical, and both device-built structures equal their CPU builds; the
//! suite stops otherwise. It exists to show what the sparse table the renderer queries costs and
//! gains against the usual hierarchy.

use super::example::Example;
use crate::bench::harness::{time_cpu, time_gpu, Bench, Throughput};
use crate::bench::plot::bar_chart;
use anyhow::{ensure, Context};
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::glint::minmax_mip::{brute_force, random_squares, table_query, MinMaxMip};
use lazysolid_renderer::glint::range_table::quantize_texels;
use lazysolid_renderer::glint::{
    gpu_range_query::range_query_kernel, record_range_queries, record_range_table, GpuMinMaxMip,
    RangeMethod, RangeTable,
};
use lazysolid_renderer::kernels::render::GLINT_RANGE_LEVEL;

/// What the structures part measured for one size (for the summary and the figures).
pub(super) struct SizeResult {
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

#[allow(clippy::too_many_arguments)]
pub(super) fn measure_structures(
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

pub(super) fn print_structures(results: &[SizeResult], queries: usize) {
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

pub(super) fn figures(bench: &Bench, results: &[SizeResult]) -> anyhow::Result<()> {
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
