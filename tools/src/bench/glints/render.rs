//! The render part: the glint material's render time on a scene (`scenes/glints.toml`): the
//! pruned traversal against the explicit reference (every texel of each footprint, the ratio the
//! paper reports as +3 % to +53 %) and against the plain conductor. It exists because the
//! structures' query rates say nothing of what the material costs inside a path tracer.

use super::GlintsArgs;
use crate::bench::harness::{Bench, Throughput};
use crate::cli::resolution::Resolution;
use anyhow::ensure;
use lazysolid_renderer::glint::GlintCase;
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{MaterialKind, Scene};
use std::time::Duration;

/// The render part's scene at the asked size and samples, refused before anything is measured
/// when it has no glint material.
pub(super) fn render_scene(args: &GlintsArgs) -> anyhow::Result<Scene> {
    let (res, spp) = if args.quick {
        (
            Resolution {
                width: 64,
                height: 48,
            },
            2,
        )
    } else {
        (args.render_res, args.spp)
    };
    res.check("--render-res", 1..=4096)?;
    ensure!(
        (1..=4096).contains(&spp),
        "--spp {spp}: must lie in 1..=4096"
    );
    let mut scene = Scene::load(&args.scene)?;
    ensure!(
        scene
            .materials
            .iter()
            .any(|m| m.kind == MaterialKind::Glint),
        "--scene {}: has no kind = \"glint\" material to measure",
        args.scene.display()
    );
    scene.render.width = res.width;
    scene.render.height = res.height;
    scene.render.spp = spp;
    Ok(scene)
}

/// The glint material's render time: the scene with its glints evaluated by the pruned
/// traversal, by the explicit reference (every texel of each footprint), and replaced by the
/// plain conductor they are made of. Each run builds the path tracer anew and times its
/// passes only (the device work of tracing and shading, not the scene's preparation).
pub(super) fn render_part(
    bench: &mut Bench,
    gpu: &lazysolid_compute::gpu::Gpu,
    scene: &Scene,
    args: &GlintsArgs,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let r = &scene.render;
    let name = args
        .scene
        .file_name()
        .map_or_else(|| "scene".into(), |n| n.to_string_lossy().into_owned());
    let case = format!("render {name} {}×{} {} spp", r.width, r.height, r.spp);
    let samples = u64::from(r.width) * u64::from(r.height) * u64::from(r.spp);
    let mut mins = Vec::new();
    for c in GlintCase::ALL {
        bench.status(format!("{case}: {}", c.name()));
        let s = c.apply(scene);
        let baseline = match c {
            GlintCase::Pruned => Some(GlintCase::Explicit.name()),
            _ => None,
        };
        let min = bench.case(
            &case,
            samples,
            c.name(),
            Throughput::Items("sample"),
            baseline,
            || {
                let mut tracer = PathTracer::new(gpu, &s)?;
                let mut time = Duration::ZERO;
                tracer.render(|p| time += p.time)?;
                Ok(time.as_secs_f64() * 1e3)
            },
        )?;
        mins.push((c, min));
    }
    let ms = |case: GlintCase| mins.iter().find(|m| m.0 == case).map_or(f64::NAN, |m| m.1);
    let pruned = ms(GlintCase::Pruned);
    let explicit = ms(GlintCase::Explicit);
    let conductor = ms(GlintCase::ALL[2]);
    let over_explicit = (pruned / explicit - 1.0) * 100.0;
    let over_conductor = pruned / conductor;
    println!(
        "render ({case}, min of {} runs): conductor {conductor:.0} ms, glint explicit \
         {explicit:.0} ms, glint pruned {pruned:.0} ms: {over_explicit:+.0} % against the \
         explicit reference (paper: +3 % to +53 % against Yan et al. 2016), {over_conductor:.1}× \
         the conductor",
        bench
            .rows()
            .last()
            .map_or(0, |row| row.stats.samples_ms.len())
    );
    notes.push((format!("{case}: pruned over explicit %"), over_explicit));
    notes.push((format!("{case}: pruned / conductor"), over_conductor));
    Ok(())
}
