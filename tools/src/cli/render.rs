//! `lazysolid render SCENE.toml -o out.png`: path-trace a scene file on the device.

use super::output::check_writable;
use super::resolution::Resolution;
use super::GlobalArgs;
use anyhow::{ensure, Context};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use lazysolid_renderer::output::{write_exr, write_png, Operator, ToneMap};
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::Scene;
use std::path::PathBuf;
use std::time::Instant;

/// Tone-mapping curves for the PNG.
#[derive(Clone, Copy, ValueEnum)]
pub enum ToneCurve {
    /// Clip to [0, 1].
    Clamp,
    /// x / (1 + x).
    Reinhard,
    /// The fitted ACES filmic curve.
    Aces,
}

/// What to render and where to write it.
#[derive(Args)]
pub struct RenderArgs {
    /// The scene file (TOML; see docs/scenes.md).
    pub scene: PathBuf,
    /// The tone-mapped 8-bit PNG to write (its folder must exist: checked before rendering).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the HDR film (with albedo, normal and depth layers) as OpenEXR; default:
    /// the PNG's path with the extension .exr.
    #[arg(long)]
    pub exr: Option<PathBuf>,
    /// Do not write the EXR.
    #[arg(long, conflicts_with = "exr")]
    pub no_exr: bool,
    /// Samples per pixel, overriding the scene's.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Image size WxH in pixels (N for NxN), overriding the scene's.
    #[arg(long, value_name = "WxH")]
    pub res: Option<Resolution>,
    /// Seed of the random numbers, overriding the scene's.
    #[arg(long)]
    pub seed: Option<u32>,
    /// Exposure in stops applied before tone mapping.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    pub exposure: f32,
    /// Tone-mapping curve of the PNG.
    #[arg(long, value_enum, default_value_t = ToneCurve::Aces)]
    pub tonemap: ToneCurve,
}

/// Runs the command.
pub fn run(args: &RenderArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let exr = if args.no_exr {
        None
    } else {
        Some(
            args.exr
                .clone()
                .unwrap_or_else(|| args.output.with_extension("exr")),
        )
    };
    check_writable("-o", &args.output)?;
    if let Some(exr) = &exr {
        check_writable("--exr", exr)?;
    }
    let mut scene = Scene::load(&args.scene)?;
    if let Some(spp) = args.spp {
        ensure!(
            (1..=1_048_576).contains(&spp),
            "--spp {spp} is out of range (1..=1048576)"
        );
        scene.render.spp = spp;
    }
    if let Some(res) = args.res {
        res.check("--res", 1..=8192)?;
        scene.render.width = res.width;
        scene.render.height = res.height;
    }
    if let Some(seed) = args.seed {
        scene.render.seed = seed;
    }
    let gpu = global.gpu()?;
    let start = Instant::now();
    let mut tracer = PathTracer::new(&gpu, &scene)
        .with_context(|| format!("preparing {}", args.scene.display()))?;
    let stats = tracer.stats();
    let s = scene.render;
    eprintln!(
        "{}: {}x{}, {} spp, {} instances, {} triangles, BVH {:.1} MB built in {:.0} ms",
        args.scene.display(),
        s.width,
        s.height,
        s.spp,
        scene.instances.len(),
        stats.instanced_triangles,
        stats.bvh_bytes as f64 / 1e6,
        (stats.blas_time + stats.tlas_time).as_secs_f64() * 1e3
    );
    for b in tracer.stores() {
        eprintln!(
            "baked {:?} on {:?} into {} at R = {}: {} texels, {:.1} MB, {:.2} s",
            b.material,
            b.mesh,
            b.kind,
            b.resolution,
            b.texels,
            b.bytes as f64 / 1e6,
            b.build_time.as_secs_f64()
        );
        if let Some(s) = b.synthesis {
            eprintln!(
                "  synthesized lazily: {} voxel versions over all levels, {} voxels at the \
                 finest, {:.1} MB of kept synthesis state",
                s.versions,
                s.finest,
                s.state_bytes as f64 / 1e6
            );
        }
    }
    let bar = ProgressBar::new(s.spp as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} spp  {msg}  eta {eta}",
        )
        .expect("valid template"),
    );
    let mut rays = 0u64;
    let mut trace_time = 0.0f64;
    let film = tracer.render(|pass| {
        rays += pass.rays;
        trace_time += pass.time.as_secs_f64();
        bar.set_position(pass.samples as u64);
        bar.set_message(format!(
            "{:.2} Mrays/s",
            pass.rays as f64 / pass.time.as_secs_f64() / 1e6
        ));
    })?;
    bar.finish_and_clear();
    let tone_map = ToneMap {
        exposure_ev: args.exposure,
        operator: match args.tonemap {
            ToneCurve::Clamp => Operator::Clamp,
            ToneCurve::Reinhard => Operator::Reinhard,
            ToneCurve::Aces => Operator::AcesFitted,
        },
    };
    write_png(&film, &args.output, &tone_map)?;
    if let Some(exr) = &exr {
        write_exr(&film, exr)?;
    }
    eprintln!(
        "rendered {} spp in {:.2} s ({:.2} Mrays/s, {} rays), total {:.2} s",
        tracer.samples(),
        trace_time,
        rays as f64 / trace_time / 1e6,
        rays,
        start.elapsed().as_secs_f64()
    );
    println!("image: {}", args.output.display());
    if let Some(exr) = &exr {
        println!("hdr:   {}", exr.display());
    }
    Ok(())
}
