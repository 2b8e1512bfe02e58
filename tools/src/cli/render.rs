//! `lazysolid render SCENE.toml -o out.png`: path-trace a scene file on the device.

use super::components::components;
use super::output::check_writable;
use super::resolution::Resolution;
use super::GlobalArgs;
use anyhow::{bail, ensure, Context};
use clap::{Args, ValueEnum};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};
use lazysolid_renderer::export::{export_broken, ExportOptions};
use lazysolid_renderer::output::{
    preview_frame, write_exr, write_gif, write_png, Operator, ToneMap,
};
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{Camera, Scene};
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
    /// Render the still at frame K of the scene's [animation] (time K / fps) instead of time
    /// 0; with --frames, the still is rendered too (at the [render] size and samples) before
    /// the sequence, from the same baked stores.
    #[arg(long, value_name = "K")]
    pub frame: Option<u32>,
    /// Render frames A to B (both included) of the scene's [animation], at its size and
    /// samples: numbered PNGs (`-o out.png` gives out_0000.png, ...), numbered EXRs only when
    /// --exr is given, and an animated preview out.gif.
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    pub frames: Option<(u32, u32)>,
    /// Eye position X,Y,Z, overriding the scene camera's: with --look-at and --fov, another
    /// view of the same scene (a close-up of one crack) without a second scene file.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    pub camera: Option<Vec3>,
    /// Point X,Y,Z the camera looks at, overriding the scene's.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_hyphen_values = true)]
    pub look_at: Option<Vec3>,
    /// Vertical field of view in degrees, in (0, 180), overriding the scene's.
    #[arg(long, value_name = "DEG")]
    pub fov: Option<f32>,
    /// Export every cut or fractured instance with its matter into DIR (created if missing):
    /// `<mesh>.glb` (a node per piece, its baked atlas as base colour, the explosion as
    /// animation) and `<mesh>/piece_NNN.obj` + `.mtl` + `.png` (docs/fracture.md, "Export").
    #[arg(long, value_name = "DIR")]
    pub export: Option<PathBuf>,
    /// Texel density of the exported atlases, texels per unit of the mesh's unit cube
    /// (default: the store's resolution, one texel per voxel).
    #[arg(long, value_name = "TEXELS", requires = "export")]
    pub export_density: Option<f32>,
    /// Mip levels the exported atlases must not bleed through: charts get 2^K texels of
    /// padding filled with their border colours.
    #[arg(long, value_name = "K", default_value_t = 3, requires = "export")]
    pub export_mips: u32,
}

fn parse_point(value: &str) -> Result<Vec3, String> {
    let p: [f32; 3] = components(value, " (e.g. 0.4,1.2,-2)", "a number")?;
    let p = Vec3::from_array(p);
    if !p.is_finite() {
        return Err(format!("{value:?} is not finite"));
    }
    Ok(p)
}

/// The scene's camera with the command line's position, look-at point and field of view.
fn override_camera(args: &RenderArgs, camera: &mut Camera) -> anyhow::Result<()> {
    if let Some(p) = args.camera {
        camera.position = p;
    }
    if let Some(p) = args.look_at {
        camera.look_at = p;
    }
    if let Some(fov) = args.fov {
        ensure!(
            fov.is_finite() && fov > 0.0 && fov < 180.0,
            "--fov {fov} is out of range (0, 180) degrees"
        );
        camera.fov_y_deg = fov;
    }
    let view = camera.look_at - camera.position;
    ensure!(
        view.length() > 0.0,
        "--camera/--look-at: the camera is at the point it looks at ({}), so it has no view direction",
        camera.position
    );
    ensure!(
        view.normalize().cross(camera.up.normalize()).length() >= 1e-3,
        "--camera/--look-at: the view direction {} is parallel to the camera's up {}",
        view.normalize(),
        camera.up
    );
    Ok(())
}

fn parse_frames(value: &str) -> Result<(u32, u32), String> {
    let (a, b) = value
        .split_once("..")
        .ok_or_else(|| format!("{value:?}: expected A..B, e.g. 0..23"))?;
    let parse = |s: &str| {
        s.trim()
            .parse::<u32>()
            .map_err(|e| format!("{value:?}: {s:?} is not a frame number ({e})"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if a > b {
        return Err(format!("{value:?}: the first frame is after the last"));
    }
    Ok((a, b))
}

/// `dir/stem.ext` with the frame number: `dir/stem_0007.ext`.
fn numbered(path: &std::path::Path, frame: u32) -> PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let ext = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    path.with_file_name(format!("{stem}_{frame:04}{ext}"))
}

/// Runs the command.
pub fn run(args: &RenderArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    // The still's EXR: as asked, or next to its PNG unless --no-exr (a sequence alone writes
    // EXRs only when --exr is given).
    let still = args.frames.is_none() || args.frame.is_some();
    let exr = match (&args.exr, args.no_exr || !still) {
        (Some(e), _) => Some(e.clone()),
        (None, true) => None,
        (None, false) => Some(args.output.with_extension("exr")),
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
    override_camera(args, &mut scene.camera)?;
    let frames: Vec<u32> = args.frames.map_or(vec![], |(a, b)| (a..=b).collect());
    if let Some(last) = frames.iter().chain(&args.frame).max().copied() {
        let Some(animation) = scene.animation else {
            bail!(
                "--frame/--frames: {} has no [animation] table (frames, fps)",
                args.scene.display()
            );
        };
        ensure!(
            last < animation.frames,
            "--frame/--frames: frame {last} is past the scene's last frame {} ([animation] frames = {})",
            animation.frames - 1,
            animation.frames
        );
    }
    let gpu = global.gpu()?;
    let start = Instant::now();
    let mut tracer = PathTracer::new(&gpu, &scene)
        .with_context(|| format!("preparing {}", args.scene.display()))?;
    let prepare = start.elapsed();
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
    report_pieces(&scene);
    report_maps(&scene);
    report_stores(&tracer);
    eprintln!("prepared in {:.2} s", prepare.as_secs_f64());
    if let Some(dir) = &args.export {
        export(&scene, &tracer, dir, args)?;
    }
    let tone_map = ToneMap {
        exposure_ev: args.exposure,
        operator: match args.tonemap {
            ToneCurve::Clamp => Operator::Clamp,
            ToneCurve::Reinhard => Operator::Reinhard,
            ToneCurve::Aces => Operator::AcesFitted,
        },
    };
    let sequence_settings = scene.animation.map(|a| {
        let mut r = scene.render;
        (r.width, r.height, r.spp) = (a.width, a.height, a.spp);
        if let Some(res) = args.res {
            (r.width, r.height) = (res.width, res.height);
        }
        if let Some(spp) = args.spp {
            r.spp = spp;
        }
        r
    });
    let still = frames.is_empty() || args.frame.is_some();
    let total = still as u64 * s.spp as u64
        + frames.len() as u64 * sequence_settings.map_or(0, |r| r.spp as u64);
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} samples  {msg}  eta {eta}",
        )
        .expect("valid template"),
    );
    let mut done = 0u64;
    let mut shoot = |tracer: &mut PathTracer, frame: Option<u32>| -> anyhow::Result<_> {
        let frame_start = Instant::now();
        // The tracer starts at rest (time 0): only a frame moves the instances.
        if let Some(f) = frame {
            tracer.set_time(&scene, scene.frame_time(f))?;
        }
        let (mut rays, mut trace_time) = (0u64, 0.0f64);
        let film = tracer.render(|pass| {
            rays += pass.rays;
            trace_time += pass.time.as_secs_f64();
            bar.set_position(done + pass.samples as u64);
            let rate = pass.rays as f64 / pass.time.as_secs_f64() / 1e6;
            bar.set_message(match frame {
                Some(f) => format!("frame {f}, {rate:.2} Mrays/s"),
                None => format!("{rate:.2} Mrays/s"),
            });
        })?;
        done += tracer.samples() as u64;
        bar.suspend(|| {
            eprintln!(
                "{}: {}x{}, {} spp in {:.2} s ({:.2} Mrays/s, {} rays), with BVH and output {:.2} s",
                match frame {
                    Some(f) => format!("frame {f} (t = {:.3} s)", scene.frame_time(f)),
                    None => "still".to_string(),
                },
                film.width(),
                film.height(),
                tracer.samples(),
                trace_time,
                rays as f64 / trace_time / 1e6,
                rays,
                frame_start.elapsed().as_secs_f64()
            )
        });
        Ok(film)
    };
    if still {
        let film = shoot(&mut tracer, args.frame)?;
        write_png(&film, &args.output, &tone_map)?;
        if let Some(exr) = &exr {
            write_exr(&film, exr)?;
        }
    }
    let mut written = Vec::new();
    if let (Some(settings), false) = (sequence_settings, frames.is_empty()) {
        tracer.set_settings(&scene, settings)?;
        let mut previews = Vec::with_capacity(frames.len());
        let gif = args.output.with_extension("gif");
        for &f in &frames {
            let film = shoot(&mut tracer, Some(f))?;
            let png = numbered(&args.output, f);
            write_png(&film, &png, &tone_map)?;
            if let Some(exr) = &args.exr {
                write_exr(&film, numbered(exr, f))?;
            }
            previews.push(preview_frame(&film, &gif, &tone_map)?);
            written.push(png);
        }
        write_gif(&gif, &previews, scene.animation.map_or(24.0, |a| a.fps))?;
    }
    bar.finish_and_clear();
    eprintln!("total {:.2} s", start.elapsed().as_secs_f64());
    if still {
        println!("image: {}", args.output.display());
        if let Some(exr) = &exr {
            println!("hdr:   {}", exr.display());
        }
    }
    if let (Some(first), Some(last)) = (written.first(), written.last()) {
        println!(
            "frames: {} .. {} ({} PNG{})",
            first.display(),
            last.display(),
            written.len(),
            if args.exr.is_some() { " and EXR" } else { "" }
        );
        println!("animation: {}", args.output.with_extension("gif").display());
    }
    Ok(())
}

/// `--export`: the broken instances with their matter, and what was written.
fn export(
    scene: &Scene,
    tracer: &PathTracer,
    dir: &std::path::Path,
    args: &RenderArgs,
) -> anyhow::Result<()> {
    let start = Instant::now();
    let options = ExportOptions {
        texels_per_unit: args.export_density,
        mip_levels: args.export_mips,
    };
    let objects = export_broken(scene, tracer.scene_stores(), dir, &options)?;
    ensure!(
        !objects.is_empty(),
        "--export {}: the scene breaks no instance ([[cut]] or [[fracture]]), so there is nothing to export",
        dir.display()
    );
    for o in &objects {
        let (texels, holes, charts) = (o.covered(), o.holes(), o.charts());
        let animation = if o.times > 1 {
            format!(", explosion animated over {} frames", o.times)
        } else {
            String::new()
        };
        eprintln!(
            "export: {} ({} pieces{animation}; atlases at {} texels per unit, padding {} texels, {charts} charts, {texels} texels of matter{})",
            o.glb.display(),
            o.pieces.len(),
            o.texels_per_unit,
            o.padding,
            if holes > 0 { format!(", {holes} with no stored matter (magenta)") } else { String::new() },
        );
        eprintln!(
            "export: {}/piece_*.obj with .mtl and .png (map_Kd)",
            dir.join(&o.name).display()
        );
    }
    eprintln!("exported in {:.2} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// Per broken instance, its pieces and the self-intersections its caps resolved (a scanned
/// mesh often intersects itself; the cut still closes every piece, and says where it had to).
fn report_pieces(scene: &Scene) {
    let mut broken: std::collections::BTreeMap<usize, (usize, usize, usize, &str)> =
        Default::default();
    for inst in &scene.instances {
        if let Some(p) = &inst.piece {
            let name = scene.meshes[inst.mesh].name.as_str();
            let entry = broken.entry(p.broken).or_insert((0, 0, 0, name));
            entry.0 += 1;
            entry.1 += p.resolved_crossings;
            entry.2 += p.separated_vertices;
        }
    }
    for (index, (pieces, crossings, separated, name)) in broken {
        let mesh = name.split('#').next().unwrap_or(name);
        let mut resolved = if crossings > 0 {
            format!(
                "; {crossings} crossing(s) of its self-intersecting surface resolved in the caps"
            )
        } else {
            String::new()
        };
        if separated > 0 {
            resolved += &format!(
                "; its sheets separated where they met ({separated} vertex copies and edge splits)"
            );
        }
        eprintln!(
            "[[instance]] {} ({mesh}): broken into {pieces} closed pieces{resolved}",
            index + 1
        );
    }
}

/// How each normal, height or glint map became its example (cut or resampled to a square
/// power-of-two grid), so a map of any size says what was done to it.
fn report_maps(scene: &Scene) {
    for m in &scene.materials {
        let maps = m.normal_map.as_ref().map(|n| ("normal map", &n.fit));
        let glint = m.glint.as_ref().map(|g| ("glint example", &g.fit));
        for (what, fit) in maps.into_iter().chain(glint) {
            eprintln!("material {:?}: {what} {fit}", m.name);
        }
        if let Some(a) = &m.albedo_map {
            if let Some((step, trees)) = &a.ctree {
                eprintln!(
                    "material {:?}: albedo map {} read through compressed trees at step {step}: {}",
                    m.name,
                    a.source.display(),
                    ctree_summary(&a.image, trees)
                );
            }
        }
    }
}

/// Bytes, bits per texel and PSNR against the image of an albedo map's trees.
fn ctree_summary(
    image: &lazysolid_renderer::image_texture::ImageTexture,
    trees: &lazysolid_compute::ctree::colour::ColourTrees,
) -> String {
    let original: Vec<u8> = image.levels[0]
        .iter()
        .flat_map(|&t| [t as u8, (t >> 8) as u8, (t >> 16) as u8])
        .collect();
    let decoded = trees.decode();
    let se: f64 = original
        .iter()
        .zip(&decoded)
        .map(|(&a, &b)| (a as f64 - b as f64).powi(2))
        .sum();
    let mse = se / original.len() as f64;
    let psnr = if mse == 0.0 {
        "lossless".to_string()
    } else {
        format!("PSNR {:.2} dB", 10.0 * (255.0f64 * 255.0 / mse).log10())
    };
    let bytes = trees.size_bytes();
    let texels = (image.width * image.height) as f64;
    format!(
        "{bytes} bytes, {:.2} bits per texel (the RGBA8 image: 32), {psnr}",
        8.0 * bytes as f64 / texels
    )
}

/// What the scene's stores hold and what synthesizing and cutting them cost.
fn report_stores(tracer: &PathTracer) {
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
        if let Some(fit) = &b.exemplar {
            eprintln!("  exemplar fit: {fit}");
        }
        if let Some(s) = b.synthesis {
            eprintln!(
                "  synthesized lazily: {} voxel versions over all levels, {} voxels at the \
                 finest, {:.1} MB of kept synthesis state, {:.2} s",
                s.versions,
                s.finest,
                s.state_bytes as f64 / 1e6,
                s.time.as_secs_f64()
            );
        }
        if let Some(c) = b.cut {
            eprintln!(
                "  cut faces: {} triangles needing {} voxels, {} new; store +{} texels, {:.2} -> {:.2} MB; {:.2} s",
                c.cap_triangles,
                c.requested_voxels,
                c.new_voxels,
                c.texels_added,
                c.bytes_before as f64 / 1e6,
                c.bytes_after as f64 / 1e6,
                c.time.as_secs_f64()
            );
            if let Some(s) = c.synthesis {
                eprintln!(
                    "    synthesized {} new voxel versions in {:.2} s (kept state now {:.1} MB)",
                    s.versions,
                    s.time.as_secs_f64(),
                    s.state_bytes as f64 / 1e6
                );
            }
        }
    }
}
