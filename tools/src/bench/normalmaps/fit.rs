//! The fit part: the vMF pyramid's EM fit time and memory per map size and lobe count, on
//! generated bump-and-scratch height fields (the glint suite's), beside the plain MIP's memory.
//! The thesis fits a 512² map "in under 2 minutes" (seed 000, T:3391–3397).

use super::NormalMapsArgs;
use crate::bench::harness::{time_cpu, Bench, Throughput};
use lazysolid_renderer::glint::synthetic::{bumps_and_scratches, BumpExtent};
use lazysolid_renderer::glint::NormalExample;
use lazysolid_renderer::normal_map::gpu_fit::GpuVmfFitter;
use lazysolid_renderer::normal_map::pyramid::{VmfPyramid, LOBES_PER_TEXEL};

/// Refuses sizes and lobe counts the fit does not take, before anything is measured.
pub(super) fn check(args: &NormalMapsArgs) -> anyhow::Result<()> {
    for &n in &args.fit_sizes {
        anyhow::ensure!(
            n.is_power_of_two() && (8..=2048).contains(&n),
            "--fit-sizes {n}: must be a power of two from 8 to 2048"
        );
    }
    for &j in &args.lobes {
        anyhow::ensure!(
            LOBES_PER_TEXEL.contains(&j),
            "--lobes {j}: must lie in {}..={}",
            LOBES_PER_TEXEL.start(),
            LOBES_PER_TEXEL.end()
        );
    }
    Ok(())
}

/// Texels of every level of an `n`² pyramid.
fn pyramid_texels(n: usize) -> u64 {
    let mut total = 0u64;
    let mut e = n as u64;
    loop {
        total += e * e;
        if e == 1 {
            return total;
        }
        e /= 2;
    }
}

/// Times the fits on the CPU and on the device and notes the memory of each representation.
pub(super) fn run(
    bench: &mut Bench,
    gpu: &lazysolid_compute::gpu::Gpu,
    args: &NormalMapsArgs,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    for &n in &args.fit_sizes {
        let heights = bumps_and_scratches(n, args.seed, BumpExtent::FourSigma);
        let map = NormalExample::from_heights("generated bumps and scratches", n, &heights)?;
        let texels = pyramid_texels(n);
        notes.push((format!("{n}² plain MIP bytes (RGBA8)"), (texels * 4) as f64));
        notes.push((format!("{n}² SH9 bytes (f32)"), (texels * 36) as f64));
        for &j in &args.lobes {
            let case = format!("vMF fit {n}² J={j}");
            bench.status(case.clone());
            bench.case(
                &case,
                (n * n) as u64,
                "EM on the CPU",
                Throughput::Items("texel"),
                None,
                || {
                    let (p, ms) = time_cpu(|| VmfPyramid::build(&map, j));
                    p.map_err(anyhow::Error::msg)?;
                    Ok(ms)
                },
            )?;
            bench.set_builder("cpu");
            let fitter = GpuVmfFitter::new(gpu, &map)?;
            bench.case(
                &case,
                (n * n) as u64,
                "EM on the device (f32, starts on the host)",
                Throughput::Items("texel"),
                Some("EM on the CPU"),
                || {
                    let (p, ms) = time_cpu(|| fitter.build(j));
                    p?;
                    Ok(ms)
                },
            )?;
            bench.set_builder("gpu");
            notes.push((
                format!("{n}² vMF J={j} bytes (f32 α, α·r)"),
                (texels * j as u64 * 16) as f64,
            ));
        }
    }
    Ok(())
}
