//! `lazysolid bench prims`: the GPU primitives against their CPU references, and the scan
//! against a plain copy kernel's bandwidth, all measured in one run.

use super::harness::{time_cpu, Bench, Throughput};
use super::CommonArgs;
use crate::cli::GlobalArgs;
use anyhow::ensure;
use clap::Args;
use lazysolid_compute::gpu::{Gpu, GpuBuffer, Recorder};
use lazysolid_compute::kernels;
use lazysolid_compute::prims::{
    compact_cpu, exclusive_scan_cpu,
    push::{CopyCountPush, CopyPush},
    reduce_cpu, CompactOutput, Compactor, Keep, KeepCpu, RadixSort, Reduce, ReduceOp, Scan,
};
use rand::{Rng, SeedableRng};

/// Sizes of the primitive benchmarks.
#[derive(Args)]
pub struct PrimsArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Elements of the scan, reduce, compaction and copy cases.
    #[arg(long, default_value_t = 64 << 20)]
    pub scan_elements: usize,
    /// Elements of the radix-sort cases.
    #[arg(long, default_value_t = 16 << 20)]
    pub sort_elements: usize,
    /// Divide every size by 16 (a quick look, not the reference measurement).
    #[arg(long)]
    pub quick: bool,
}

/// Times recorded GPU work with timestamps around it, in ms; `setup` is recorded before the
/// first timestamp (e.g. restoring an input that the measured work overwrites).
fn gpu_ms(
    gpu: &Gpu,
    setup: impl FnOnce(&mut Recorder<'_>) -> lazysolid_compute::gpu::GpuResult<()>,
    work: impl FnOnce(&mut Recorder<'_>) -> lazysolid_compute::gpu::GpuResult<()>,
) -> anyhow::Result<f64> {
    let ((), t) = gpu.submit_timed(|rec| {
        setup(rec)?;
        rec.timestamp()?;
        work(rec)?;
        rec.timestamp()
    })?;
    Ok((t[1] - t[0]) * 1e-6)
}

fn no_setup(_: &mut Recorder<'_>) -> lazysolid_compute::gpu::GpuResult<()> {
    Ok(())
}

/// Runs the suite.
pub fn run(args: &PrimsArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let scale = if args.quick { 16 } else { 1 };
    let n = args.scan_elements / scale;
    let sort_n = args.sort_elements / scale;
    ensure!(n >= 1 && sort_n >= 1, "sizes must be at least 1 element");
    let gpu = global.gpu()?;
    let mut bench = Bench::new("bench-prims", &gpu, &args.common, 13)?;
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(0x5eed);
    let mut notes = Vec::new();

    // Copy: the bandwidth reference for the scan. The plain copy a user would write binds its
    // buffers; past maxStorageBufferRange it binds them in ranges. The device-address copy is
    // shown too (slower on lavapipe).
    let input: Vec<u32> = (0..n).map(|_| rng.random_range(0..1000)).collect();
    let src = GpuBuffer::from_slice(&gpu, "bench input", &input)?;
    let dst = GpuBuffer::<u32>::new(&gpu, "bench output", n)?;
    let copy_quads = gpu.kernel(&kernels::prims::COPY_QUADS)?;
    let copy_addr = gpu.kernel(&kernels::prims::COPY_VEC4)?;
    let bytes = 8 * n as u64;
    let chunk = (gpu.info().max_storage_buffer_range as usize / 4) & !3;
    let case = "copy (read + write)";
    let copy_ms = bench.case(
        case,
        n as u64,
        "gpu copy kernel (bound uvec4)",
        Throughput::Bytes(bytes),
        Some("cpu memcpy (1 thread)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                for first in (0..n).step_by(chunk) {
                    let words = chunk.min(n - first);
                    let quads = words.div_ceil(4);
                    let bindings = [
                        ("Src", src.arg_range(first, words)?),
                        ("Dst", dst.arg_range(first, words)?),
                    ];
                    rec.dispatch(
                        &copy_quads,
                        copy_quads.groups_for(quads as u64),
                        &bindings,
                        &CopyCountPush { n: quads as u32 },
                    )?;
                }
                Ok(())
            })
        },
    )?;
    ensure!(
        n % 4 != 0 || dst.read()? == input,
        "the copy kernel disagrees with its input"
    );
    let copy_push = CopyPush {
        src: src.address(),
        dst: dst.address(),
        n: n as u32,
    };
    bench.case(
        case,
        n as u64,
        "gpu copy kernel (device address uvec4)",
        Throughput::Bytes(bytes),
        Some("gpu copy kernel (bound uvec4)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                rec.dispatch(
                    &copy_addr,
                    copy_addr.groups_for(n.div_ceil(4) as u64),
                    &[],
                    &copy_push,
                )
            })
        },
    )?;
    bench.case(
        case,
        n as u64,
        "cpu memcpy (1 thread)",
        Throughput::Bytes(bytes),
        None,
        || {
            let mut out = vec![0u32; n];
            Ok(time_cpu(|| out.copy_from_slice(&input)).1)
        },
    )?;

    // Exclusive scan.
    let case = "exclusive scan u32";
    let mut scan = Scan::new(&gpu)?;
    let total = GpuBuffer::<u32>::new(&gpu, "scan total", 1)?;
    let scan_ms = bench.case(
        case,
        n as u64,
        "gpu",
        Throughput::Bytes(bytes),
        Some("cpu reference (1 thread)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                scan.record(rec, &src, &dst, n, Some(&total))
            })
        },
    )?;
    let (expected, expected_total) = exclusive_scan_cpu(&input);
    ensure!(
        dst.read()? == expected && total.read()?[0] == expected_total,
        "GPU scan disagrees with the CPU reference"
    );
    bench.case(
        case,
        n as u64,
        "cpu reference (1 thread)",
        Throughput::Bytes(bytes),
        None,
        || Ok(time_cpu(|| exclusive_scan_cpu(&input)).1),
    )?;
    notes.push((
        "scan bandwidth / bound copy kernel bandwidth (target >= 0.5)".to_string(),
        copy_ms / scan_ms,
    ));

    // Reduce.
    let case = "reduce sum u32";
    let mut reduce = Reduce::new(&gpu)?;
    let result = GpuBuffer::<u32>::new(&gpu, "reduce result", 1)?;
    bench.case(
        case,
        n as u64,
        "gpu",
        Throughput::Elements,
        Some("cpu reference (1 thread)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                reduce.record(rec, &src, n, ReduceOp::Sum, &result)
            })
        },
    )?;
    ensure!(
        result.read()?[0] == reduce_cpu(&input, ReduceOp::Sum),
        "GPU reduce disagrees with the CPU reference"
    );
    bench.case(
        case,
        n as u64,
        "cpu reference (1 thread)",
        Throughput::Elements,
        None,
        || Ok(time_cpu(|| reduce_cpu(&input, ReduceOp::Sum)).1),
    )?;

    // Compaction, half kept: by sentinel (every other value range replaced by u32::MAX), and
    // by flags.
    let case = "compaction u32 (50% kept)";
    let mut compactor = Compactor::new(&gpu)?;
    let count = GpuBuffer::<u32>::new(&gpu, "compaction count", 1)?;
    let sparse: Vec<u32> = input
        .iter()
        .map(|&v| if v < 500 { v } else { u32::MAX })
        .collect();
    let sparse_buf = GpuBuffer::from_slice(&gpu, "compaction values with sentinels", &sparse)?;
    let flags: Vec<u32> = input.iter().map(|&v| (v < 500) as u32).collect();
    let flags_buf = GpuBuffer::from_slice(&gpu, "compaction flags", &flags)?;
    let expected = compact_cpu(&input, KeepCpu::Flags(&flags), CompactOutput::Values);
    bench.case(
        case,
        n as u64,
        "cpu reference (1 thread)",
        Throughput::Elements,
        None,
        || Ok(time_cpu(|| compact_cpu(&input, KeepCpu::Flags(&flags), CompactOutput::Values)).1),
    )?;
    bench.case(
        case,
        n as u64,
        "gpu (by sentinel)",
        Throughput::Elements,
        Some("cpu reference (1 thread)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                compactor.record(
                    rec,
                    Some(&sparse_buf),
                    Keep::NotEqual(u32::MAX),
                    n,
                    CompactOutput::Values,
                    &dst,
                    &count,
                )
            })
        },
    )?;
    ensure!(
        dst.read_range(0, count.read()?[0] as usize)? == expected,
        "GPU compaction (sentinel) disagrees with the CPU reference"
    );
    bench.case(
        case,
        n as u64,
        "gpu (by flags)",
        Throughput::Elements,
        Some("cpu reference (1 thread)"),
        || {
            gpu_ms(&gpu, no_setup, |rec| {
                compactor.record(
                    rec,
                    Some(&src),
                    Keep::Flags(&flags_buf),
                    n,
                    CompactOutput::Values,
                    &dst,
                    &count,
                )
            })
        },
    )?;
    ensure!(
        dst.read_range(0, count.read()?[0] as usize)? == expected,
        "GPU compaction (flags) disagrees with the CPU reference"
    );
    drop((src, dst, flags_buf, sparse_buf));

    // Radix sort of u32 keys against std's sort_unstable on the same keys.
    let case = "sort u32 keys";
    let keys: Vec<u32> = (0..sort_n).map(|_| rng.random()).collect();
    let pristine = GpuBuffer::from_slice(&gpu, "sort input", &keys)?;
    let work = GpuBuffer::<u32>::new(&gpu, "sort keys", sort_n)?;
    let mut sort = RadixSort::new(&gpu)?;
    bench.case(
        case,
        sort_n as u64,
        "cpu std sort_unstable (1 thread)",
        Throughput::Elements,
        None,
        || {
            let mut k = keys.clone();
            Ok(time_cpu(|| k.sort_unstable()).1)
        },
    )?;
    bench.case(
        case,
        sort_n as u64,
        "gpu radix sort",
        Throughput::Elements,
        Some("cpu std sort_unstable (1 thread)"),
        || {
            gpu_ms(
                &gpu,
                |rec| rec.copy(&pristine, 0, &work, 0, sort_n),
                |rec| sort.record_u32(rec, &work, sort_n, 32),
            )
        },
    )?;
    let mut expected = keys.clone();
    expected.sort_unstable();
    ensure!(
        work.read()? == expected,
        "GPU radix sort disagrees with std"
    );
    drop((pristine, work));

    // Radix sort of u64 keys carrying u32 values.
    let case = "sort u64 keys + u32 values";
    let keys: Vec<u64> = (0..sort_n).map(|_| rng.random()).collect();
    let values: Vec<u32> = (0..sort_n as u32).collect();
    let pk = GpuBuffer::from_slice(&gpu, "sort input keys", &keys)?;
    let pv = GpuBuffer::from_slice(&gpu, "sort input values", &values)?;
    let wk = GpuBuffer::<u64>::new(&gpu, "sort keys", sort_n)?;
    let wv = GpuBuffer::<u32>::new(&gpu, "sort values", sort_n)?;
    let pairs: Vec<(u64, u32)> = keys.iter().copied().zip(values.iter().copied()).collect();
    bench.case(
        case,
        sort_n as u64,
        "cpu std sort_unstable (1 thread)",
        Throughput::Elements,
        None,
        || {
            let mut p = pairs.clone();
            Ok(time_cpu(|| p.sort_unstable_by_key(|&(k, _)| k)).1)
        },
    )?;
    bench.case(
        case,
        sort_n as u64,
        "gpu radix sort",
        Throughput::Elements,
        Some("cpu std sort_unstable (1 thread)"),
        || {
            gpu_ms(
                &gpu,
                |rec| {
                    rec.copy(&pk, 0, &wk, 0, sort_n)?;
                    rec.copy(&pv, 0, &wv, 0, sort_n)
                },
                |rec| sort.record_u64(rec, &wk, Some(&wv), sort_n, 64),
            )
        },
    )?;
    let (ek, ev) = lazysolid_compute::prims::sort_pairs_cpu(&keys, &values, 64);
    ensure!(
        wk.read()? == ek && wv.read()? == ev,
        "GPU pair sort disagrees with the CPU reference"
    );

    let rows = bench.rows();
    let ratio = |case: &str| {
        rows.iter()
            .find(|r| r.case == case && r.implementation == "gpu radix sort")
            .and_then(|r| r.ratio)
            .unwrap_or(f64::NAN)
    };
    notes.push((
        "sort u32: gpu speed-up over std sort_unstable".into(),
        ratio("sort u32 keys"),
    ));
    notes.push((
        "sort u64+u32: gpu speed-up over std sort_unstable".into(),
        ratio("sort u64 keys + u32 values"),
    ));
    bench.finish(&notes)?;
    Ok(())
}
