//! The quality part: each scene's normal map unfiltered, plain-MIP filtered and vMF filtered at
//! a few samples per pixel against the unfiltered map at many, over the whole image (FLIP) and
//! in the far field (mean relative error and bias of the luminance), where a plain MIP flattens
//! the map. A second reference with another seed gives the metric's own noise floor.

use super::NormalMapsArgs;
use crate::bench::harness::Bench;
use crate::bench::plot::{line_chart, Series};
use anyhow::Context;
use lazysolid_compute::gpu::Gpu;
use lazysolid_renderer::diff::flip_images;
use lazysolid_renderer::output::{tonemapped_rgb8, write_png, Film, ToneMap};
use lazysolid_renderer::render::PathTracer;
use lazysolid_renderer::scene::{NormalFilter, Scene};
use std::io::Write;
use std::path::Path;
use std::time::Duration;

/// The filters compared, with their names in tables and files.
const FILTERS: [(NormalFilter, &str); 3] = [
    (NormalFilter::None, "unfiltered"),
    (NormalFilter::Mip, "plain MIP"),
    (NormalFilter::Vmf, "vMF"),
];

/// Loads the scenes at the asked size, refusing any without a normal map.
pub(super) fn load_scenes(args: &NormalMapsArgs) -> anyhow::Result<Vec<(String, Scene)>> {
    args.scenes
        .iter()
        .map(|path| {
            let mut scene = Scene::load(path)?;
            anyhow::ensure!(
                scene.materials.iter().any(|m| m.normal_map.is_some()),
                "--scenes {}: has no material with a normal_map or height_map to filter",
                path.display()
            );
            scene.render.width = args.res.width;
            scene.render.height = args.res.height;
            let name = path
                .file_stem()
                .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
            Ok((name, scene))
        })
        .collect()
}

/// `scene` with every normal map read through `filter`, rendered at `spp` with `seed`.
fn variant(scene: &Scene, filter: NormalFilter, spp: u32, seed: u32) -> Scene {
    let mut s = scene.clone();
    for m in &mut s.materials {
        if let Some(n) = &mut m.normal_map {
            n.filter = filter;
        }
    }
    s.render.spp = spp;
    s.render.seed = seed;
    s
}

/// The film and the time of its passes (tracing and shading; not the scene's preparation, the
/// vMF fit included, which the fit part measures).
fn render(gpu: &Gpu, scene: &Scene) -> anyhow::Result<(Film, f64)> {
    let mut tracer = PathTracer::new(gpu, scene)?;
    let mut time = Duration::ZERO;
    let film = tracer.render(|p| time += p.time)?;
    Ok((film, time.as_secs_f64() * 1e3))
}

fn luminance(c: [f32; 3]) -> f64 {
    f64::from(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])
}

/// Mean relative error and relative bias of `test` against `reference` over the `far` pixels.
fn far_errors(reference: &Film, test: &Film, far: &[bool]) -> (f64, f64) {
    let (mut abs, mut diff, mut total) = (0.0, 0.0, 0.0);
    for ((r, t), &f) in reference.color().iter().zip(test.color()).zip(far) {
        if f {
            let (lr, lt) = (luminance(*r), luminance(*t));
            abs += (lt - lr).abs();
            diff += lt - lr;
            total += lr;
        }
    }
    if total > 0.0 {
        (abs / total, diff / total)
    } else {
        (f64::NAN, f64::NAN)
    }
}

fn srgb(film: &Film) -> anyhow::Result<image::RgbImage> {
    Ok(tonemapped_rgb8(film, &ToneMap::default())?)
}

/// One measured render.
struct QualityRow {
    scene: String,
    filter: &'static str,
    spp: u32,
    flip: f64,
    far_mre: f64,
    far_bias: f64,
    render_ms: f64,
}

/// Renders and scores every scene, filter and sample count; writes the CSV, the pictures and
/// the chart into `dir`.
pub(super) fn run(
    bench: &mut Bench,
    gpu: &Gpu,
    args: &NormalMapsArgs,
    scenes: &[(String, Scene)],
    dir: &Path,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let mut rows = Vec::new();
    for (name, scene) in scenes {
        let seed = scene.render.seed;
        bench.status(format!("{name}: reference, {} spp", args.reference_spp));
        let (reference, ref_ms) = render(
            gpu,
            &variant(
                scene,
                NormalFilter::None,
                args.reference_spp,
                seed.wrapping_add(1000),
            ),
        )?;
        let depth = reference
            .depth()
            .context("the path tracer writes the depth of the first pass")?;
        let far: Vec<bool> = depth
            .iter()
            .map(|&d| d.is_finite() && d >= args.far_distance)
            .collect();
        let far_pixels = far.iter().filter(|&&f| f).count();
        anyhow::ensure!(
            far_pixels > 0,
            "{name}: no pixel's primary hit lies beyond --far-distance {}",
            args.far_distance
        );
        write_png(
            &reference,
            dir.join(format!("{name}-reference.png")),
            &ToneMap::default(),
        )?;
        let ref_image = srgb(&reference)?;
        bench.status(format!("{name}: second reference (noise floor)"));
        let (second, _) = render(
            gpu,
            &variant(
                scene,
                NormalFilter::None,
                args.reference_spp,
                seed.wrapping_add(2000),
            ),
        )?;
        let (floor_mre, floor_bias) = far_errors(&reference, &second, &far);
        rows.push(QualityRow {
            scene: name.clone(),
            filter: "reference (2nd seed)",
            spp: args.reference_spp,
            flip: f64::from(flip_images(&ref_image, &srgb(&second)?)?.mean),
            far_mre: floor_mre,
            far_bias: floor_bias,
            render_ms: ref_ms,
        });
        println!(
            "{name}: {far_pixels} far-field pixels (primary hit beyond {}); reference {} spp in {:.1} s",
            args.far_distance,
            args.reference_spp,
            ref_ms / 1e3
        );
        for (filter, label) in FILTERS {
            for &spp in &args.spp {
                bench.status(format!("{name}: {label}, {spp} spp"));
                let (film, ms) = render(gpu, &variant(scene, filter, spp, seed))?;
                let (far_mre, far_bias) = far_errors(&reference, &film, &far);
                let flip = f64::from(flip_images(&ref_image, &srgb(&film)?)?.mean);
                let file = format!(
                    "{name}-{}-{spp}spp.png",
                    label.replace(' ', "-").to_lowercase()
                );
                write_png(&film, dir.join(file), &ToneMap::default())?;
                rows.push(QualityRow {
                    scene: name.clone(),
                    filter: label,
                    spp,
                    flip,
                    far_mre,
                    far_bias,
                    render_ms: ms,
                });
            }
        }
    }
    print_and_write(&rows, args, dir, notes)
}

fn print_and_write(
    rows: &[QualityRow],
    args: &NormalMapsArgs,
    dir: &Path,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    println!(
        "{:<16} {:<22} {:>6} {:>8} {:>12} {:>12} {:>10}",
        "scene", "filter", "spp", "FLIP", "far MRE", "far bias", "render ms"
    );
    let csv_path = dir.join("quality.csv");
    let mut csv = std::fs::File::create(&csv_path)
        .with_context(|| format!("creating {}", csv_path.display()))?;
    writeln!(
        csv,
        "scene,filter,spp,flip_mean,far_mean_relative_error,far_relative_bias,render_ms"
    )?;
    for r in rows {
        println!(
            "{:<16} {:<22} {:>6} {:>8.4} {:>12.4} {:>+12.4} {:>10.0}",
            r.scene, r.filter, r.spp, r.flip, r.far_mre, r.far_bias, r.render_ms
        );
        writeln!(
            csv,
            "{},{},{},{},{},{},{}",
            r.scene, r.filter, r.spp, r.flip, r.far_mre, r.far_bias, r.render_ms
        )?;
    }
    let scenes: Vec<&String> = {
        let mut s: Vec<&String> = rows.iter().map(|r| &r.scene).collect();
        s.dedup();
        s
    };
    for scene in scenes {
        let series: Vec<Series> = FILTERS
            .iter()
            .map(|(_, label)| Series {
                name: (*label).to_string(),
                points: rows
                    .iter()
                    .filter(|r| &r.scene == scene && r.filter == *label)
                    .map(|r| (f64::from(r.spp).log2(), r.far_mre))
                    .collect(),
            })
            .collect();
        line_chart(
            &dir.join(format!("{scene}-far-error.png")),
            &format!(
                "{scene}: far-field error against the unfiltered map at {} spp",
                args.reference_spp
            ),
            "log2 samples per pixel",
            "mean relative error (far field)",
            &series,
        )?;
        for &spp in &args.spp {
            let get = |label: &str| {
                rows.iter()
                    .find(|r| &r.scene == scene && r.filter == label && r.spp == spp)
                    .map_or(f64::NAN, |r| r.far_mre)
            };
            notes.push((
                format!("{scene} {spp} spp: far error plain MIP / vMF"),
                get("plain MIP") / get("vMF"),
            ));
        }
    }
    println!("quality table: {}", csv_path.display());
    Ok(())
}
