//! `lazysolid solid EXEMPLAR [--ex IMG] [--ey IMG] [--ez IMG] [--voxel-res N] [--offset X,Y,Z]
//! [--seed S] -o OUT.nrrd`: synthesize a box of the unbounded solid texture from 2D exemplars
//! on the device, write it as NRRD with orthogonal and oblique slices, the candidate slab and
//! a render of a cube and a sphere carved out of it (`solid_render.rs`), and score the slices
//! against their exemplars.

use super::candidate_builder::Candidates;
use super::components::components;
use super::fit_mode::Fit;
use super::output::write_png;
use super::solid_render::{carved_scene, file_name, render_carved, RENDER_SPP};
use super::tuning::{Energy, Features, OrientationRule, Schedule, SolidOrder};
use super::GlobalArgs;
use anyhow::{ensure, Context};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use lazysolid_compute::atomic_file::write_bytes_atomically;
use lazysolid_renderer::output::{Operator, ToneMap};
use lazysolid_synth::cache::DiskCache;
use lazysolid_synth::feature::feature_map;
use lazysolid_synth::quality::reachable_gap;
use lazysolid_synth::solid::{
    axis_quality, check_box, encode_nrrd, oblique, role_scorers, slice, CandidateParams,
    SolidExemplars, SolidRecipe, VolumeBox, DEFAULT_BALANCE, DEFAULT_S, DEFAULT_STRIP,
    MAX_SOLID_SIDE, MIN_SOLID_SIDE, QUALITY_SLICES, ROLE_NAMES,
};
use lazysolid_synth::EnergyKernel;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Sides `--voxel-res` accepts.
pub const SOLID_SIZES: [u32; 3] = [64, 128, 256];

/// What to synthesize and where to write it.
#[derive(Args)]
pub struct SolidArgs {
    /// The exemplar playing every role not given by --ex/--ey/--ez: PNG, JPEG or GIMP
    /// pattern, grey or colour, any size from 16 pixels a side; made square with a power-of-two
    /// side of 16 to 256 as --fit says (the line `exemplar fit:` tells what was done).
    pub exemplar: PathBuf,
    /// Exemplar of the slices perpendicular to x (image u = y, v = z).
    #[arg(long)]
    pub ex: Option<PathBuf>,
    /// Exemplar of the slices perpendicular to y (image u = x, v = z).
    #[arg(long)]
    pub ey: Option<PathBuf>,
    /// Exemplar of the slices perpendicular to z (image u = x, v = y).
    #[arg(long)]
    pub ez: Option<PathBuf>,
    /// How each image becomes a square exemplar with a power-of-two side: auto cuts the
    /// centre square of the largest power of two when that loses at most a quarter of the
    /// side and resamples to the nearest power of two otherwise (docs/solid.md).
    #[arg(long, value_enum, default_value_t = Fit::Auto)]
    pub fit: Fit,
    /// Fit the exemplars to this side (a power of two, 16 to 256) instead of the one --fit
    /// picks: smaller is faster (the candidates grow with the fourth power of the side).
    #[arg(long, value_name = "N")]
    pub exemplar_side: Option<u32>,
    /// Side of the cube to synthesize: 64, 128 or 256 voxels.
    #[arg(long, value_name = "N", default_value_t = 64)]
    pub voxel_res: u32,
    /// Absolute position X,Y,Z of the box's first voxel in the unbounded volume.
    #[arg(long, default_value = "0,0,0", value_parser = parse_offset3, allow_hyphen_values = true)]
    pub offset: [i32; 3],
    /// Seed of the jitter.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Do not render the cube and sphere carved out of the volume (NAME.render.png and the
    /// scene NAME.scene.toml it comes from).
    #[arg(long)]
    pub no_render: bool,
    /// Neither read nor write the on-disk cache of solid candidates (kept in
    /// LAZYSOLID_CACHE_DIR, else in the user's cache folder, e.g. ~/.cache/lazysolid).
    #[arg(long)]
    pub no_cache: bool,
    /// Crossbar strip length N (odd).
    #[arg(long, default_value_t = DEFAULT_STRIP)]
    pub strip: u32,
    /// Strips kept per other exemplar before the crossbar ranking (the thesis' S).
    #[arg(long, default_value_t = DEFAULT_S)]
    pub s: u32,
    /// Strength of the usage balance, 0 to 64 (0: off): a pilot synthesis measures which
    /// exemplar pixels the correction over-uses and penalizes them, so the volume keeps the
    /// exemplar's dark spots, outlines and cracks (docs/solid.md)
    #[arg(long, default_value_t = DEFAULT_BALANCE)]
    pub balance: u32,
    /// Give the usage balance to the N finest pyramid levels only [default: every level]: on
    /// a fine grain whose coarser levels hold little structure (slate), the coarser levels'
    /// penalties make the slices too contrasted at 2-4 pixels; on most exemplars they keep
    /// the structures (docs/solid.md, "The balance's levels")
    #[arg(long, value_name = "N")]
    pub balance_levels: Option<u32>,
    #[command(flatten)]
    pub energy: Energy,
    /// Where the candidates are computed (the same candidates either way): auto is the host
    /// on a CPU driver (lavapipe), the GPU otherwise.
    #[arg(long, value_enum, default_value_t = Candidates::Auto)]
    pub candidates: Candidates,
    /// The NRRD volume to write; slices and the candidate slab go next to it as
    /// NAME.x.png, NAME.y.png, NAME.z.png, NAME.oblique.png, NAME.slab.png and (with the
    /// feature channel on) NAME.features.png: each exemplar, its feature mask and distance.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub schedule: Schedule,
    #[command(flatten)]
    pub order: SolidOrder,
    #[command(flatten)]
    pub features: Features,
    #[command(flatten)]
    pub orientation: OrientationRule,
}

fn parse_offset3(s: &str) -> Result<[i32; 3], String> {
    components(s, " (e.g. -64,0,128)", "a whole number")
}

/// What the feature channel found in each distinct image: one line per image and a picture
/// of all of them stacked (none at weight 0).
struct FeatureReport {
    lines: Vec<String>,
    picture: Option<(u32, u32, Vec<[u8; 3]>)>,
}

fn feature_pictures(exemplars: &SolidExemplars) -> FeatureReport {
    if exemplars.feature_weight == 0 {
        return FeatureReport {
            lines: vec!["feature channel: off (--feature-weight 0)".into()],
            picture: None,
        };
    }
    let mut lines = Vec::new();
    let (mut width, mut height, mut pixels) = (0, 0, Vec::new());
    for image in &exemplars.images {
        let m = image.width;
        let colours: Vec<[f32; 3]> = image.rgb.iter().map(|p| p.map(f32::from)).collect();
        let map = feature_map(
            &colours,
            m,
            m,
            true,
            exemplars.feature_weight,
            exemplars.feature_mask,
        );
        lines.push(map.describe(&image.source, exemplars.feature_weight));
        let (w, h, picture) = map.picture(&image.rgb, m, m);
        width = w;
        height += h;
        pixels.extend(picture);
    }
    FeatureReport {
        lines,
        picture: Some((width, height, pixels)),
    }
}

/// `out.nrrd` → `out.SUFFIX.png`.
fn sibling(output: &Path, suffix: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.{suffix}.png"))
}

fn bar(message: &'static str, shown: bool) -> ProgressBar {
    if !shown {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{msg} [{bar:30}] level {pos}/{len} {elapsed}")
            .expect("valid template"),
    );
    bar.set_message(message);
    bar
}

impl SolidArgs {
    /// The recipe the flags describe: the defaults where a flag is absent.
    pub fn recipe(&self) -> SolidRecipe {
        SolidRecipe {
            roles: [self.ex.clone(), self.ey.clone(), self.ez.clone()],
            fit: self.fit.into(),
            exemplar_side: self.exemplar_side,
            orientation: self.orientation.rule.into(),
            feature_weight: self.features.feature_weight,
            feature_mask: self.features.feature_mask.into(),
            candidates: CandidateParams {
                strip: self.strip,
                s: self.s,
                coherence: true,
                balance: self.balance,
                balance_levels: self.balance_levels,
            },
            builder: self.candidates.into(),
            schedule: self.schedule.solid(&self.order),
            seed: self.seed,
            ..SolidRecipe::new(&self.exemplar)
        }
    }
}

/// Runs the command.
pub fn run(args: &SolidArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    ensure!(
        args.output
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("nrrd")),
        "-o {}: the output must be a .nrrd file",
        args.output.display()
    );
    ensure!(
        SOLID_SIZES.contains(&args.voxel_res),
        "--voxel-res {}: the cube side must be one of {SOLID_SIZES:?} voxels",
        args.voxel_res
    );
    check_box(VolumeBox {
        origin: args.offset,
        size: [args.voxel_res; 3],
    })
    .with_context(|| {
        format!(
            "--offset {},{},{}",
            args.offset[0], args.offset[1], args.offset[2]
        )
    })?;
    if let Some(side) = args.exemplar_side {
        ensure!(
            side.is_power_of_two() && (MIN_SOLID_SIDE..=MAX_SOLID_SIDE).contains(&side),
            "--exemplar-side {side}: must be a power of two in {MIN_SOLID_SIDE}..={MAX_SOLID_SIDE}"
        );
    }
    let recipe = args.recipe();
    recipe.candidates.check()?;
    let sources = recipe.load()?;
    let fits = sources.fits.clone();
    let mirroring = sources.mirroring;
    let gpu = global.gpu()?;
    let n = args.voxel_res;
    let cache = if args.no_cache {
        None
    } else {
        Some(DiskCache::user().context("the candidate cache (--no-cache runs without it)")?)
    };
    // The sets, then the usage balance's pilot, one step per level each.
    let b = bar("candidates", true);
    let prepared = sources.prepare(&gpu, cache.as_ref(), &mut |done, total| {
        b.set_length(total as u64);
        b.set_position(done as u64);
    })?;
    b.finish_and_clear();
    let levels = prepared.analysis.levels.len() as u64;
    let b = bar("synthesizing", true);
    b.set_length(levels);
    let window = VolumeBox {
        origin: args.offset,
        size: [n; 3],
    };
    let run = prepared
        .cube(&gpu, window, &mut |_| b.inc(1))
        .with_context(|| format!("--voxel-res {n}: the volume does not fit the device"))?;
    b.finish_and_clear();
    let exemplars = prepared.exemplars();
    let energy = EnergyKernel::new(&gpu)?;
    let quality = axis_quality(
        &energy,
        &role_scorers(exemplars),
        exemplars,
        &run.synthesis,
        &run.colours,
        args.energy.samples,
    )?;

    let notes: Vec<String> = fits.iter().map(|f| format!("exemplar fit: {f}")).collect();
    let volume = encode_nrrd(&run.colours, n, &notes);
    let render = if args.no_render {
        None
    } else {
        let start = Instant::now();
        let film = render_carved(
            &gpu,
            &run.colours,
            n,
            args.output.with_extension("scene.toml"),
            args.output.clone(),
        )?;
        Some((film, start.elapsed().as_secs_f64()))
    };

    // Everything is computed; only now are files written, each complete or not at all.
    write_bytes_atomically(&args.output, &volume)?;
    let scene_path = args.output.with_extension("scene.toml");
    let render_path = sibling(&args.output, "render");
    if let Some((film, _)) = &render {
        write_bytes_atomically(
            &scene_path,
            carved_scene(&file_name(&args.output), n).as_bytes(),
        )?;
        let tone_map = ToneMap {
            exposure_ev: 0.0,
            operator: Operator::AcesFitted,
        };
        lazysolid_renderer::output::write_png(film, &render_path, &tone_map)?;
    }
    for (axis, name) in ["x", "y", "z"].into_iter().enumerate() {
        let (rgb, _) = slice(&run.synthesis, &run.colours, axis, n / 2);
        write_png(&sibling(&args.output, name), n, n, &rgb)?;
    }
    write_png(
        &sibling(&args.output, "oblique"),
        n,
        n,
        &oblique(&run.colours, n as usize),
    )?;
    let (sw, sh, slab) = &run.slab;
    write_png(&sibling(&args.output, "slab"), *sw, *sh, slab)?;
    let features = feature_pictures(exemplars);
    if let Some((w, h, picture)) = &features.picture {
        write_png(&sibling(&args.output, "features"), *w, *h, picture)?;
    }

    let m = exemplars.side();
    println!(
        "exemplars {m}x{m}: {}",
        (0..3)
            .map(|r| format!("{} = {}", ROLE_NAMES[r], exemplars.role(r).source.display()))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for fit in &fits {
        println!("exemplar fit: {fit}");
    }
    println!("orientation: {mirroring}");
    for line in &features.lines {
        println!("{line}");
    }
    println!(
        "cube {n}^3 at ({}, {}, {}), seed {}, strip {}, S {}",
        args.offset[0], args.offset[1], args.offset[2], args.seed, args.strip, args.s
    );
    println!("analysis (CPU)    {:8.3} s", prepared.analysis_s);
    println!(
        "candidates ({:<4})  {:8.3} s ({} coherence fallbacks; cache {}{})",
        prepared.builder.name(),
        prepared.candidates_s,
        run.fallbacks,
        prepared.cached.label(),
        cache
            .as_ref()
            .map(|c| format!(" in {}", c.dir().display()))
            .unwrap_or_default()
    );
    println!(
        "synthesis (GPU)   {:8.3} s ({:.2} M voxels over all levels, {:.2} M voxel updates)",
        run.synthesis_s,
        run.voxels as f64 * 1e-6,
        run.voxel_updates as f64 * 1e-6
    );
    if let Some((_, seconds)) = &render {
        println!(
            "render (GPU)      {seconds:8.3} s (a cube and a sphere carved out of the volume, octree store, {RENDER_SPP} spp): {} (scene {})",
            render_path.display(),
            scene_path.display()
        );
    }
    println!(
        "peak GPU memory of the synthesis {:.1} MiB",
        run.peak_bytes as f64 / (1 << 20) as f64
    );
    println!(
        "triples: {:.1} % are candidates of their pixel, colour spread {:.1} (candidates {:.1})",
        100.0 * run.consistency.candidate_share,
        run.consistency.spread,
        run.consistency.candidate_spread
    );
    println!(
        "extrusion: same role coordinate one voxel along its normal x / y / z {:.1} / {:.1} / {:.1} %; coherent one pixel along the plane {:.1} / {:.1} / {:.1} %",
        100.0 * run.consistency.normal_repeat[0],
        100.0 * run.consistency.normal_repeat[1],
        100.0 * run.consistency.normal_repeat[2],
        100.0 * run.consistency.in_plane_coherence[0],
        100.0 * run.consistency.in_plane_coherence[1],
        100.0 * run.consistency.in_plane_coherence[2]
    );
    println!(
        "candidate sets: a triple continues coherently in two roles one step on (finest level) x / y / z {:.1} / {:.1} / {:.1} %",
        100.0 * run.consistency.advance_closure[0],
        100.0 * run.consistency.advance_closure[1],
        100.0 * run.consistency.advance_closure[2]
    );
    for (axis, q) in quality.iter().enumerate() {
        println!(
            "slice perpendicular to {} vs {}: SWD {:.2} ({:.2}x the exemplar's own), blockiness {:.2}, histogram distance {:.4}, period repetition {:.3}, energy {:.1}; over {} slices SWD ratio {:.2} (sd {:.2}; per band fine / mid / coarse {:.2} / {:.2} / {:.2}, band contrast {:.2} / {:.2} / {:.2}), blockiness {:.2}",
            ["x", "y", "z"][axis],
            ROLE_NAMES[axis],
            q.swd,
            q.swd_ratio,
            q.blockiness,
            q.histogram,
            q.repetition,
            q.energy,
            QUALITY_SLICES,
            q.slices_swd_ratio,
            q.slices_swd_ratio_sd,
            q.slices_swd_bands[0],
            q.slices_swd_bands[1],
            q.slices_swd_bands[2],
            q.slices_band_contrast[0],
            q.slices_band_contrast[1],
            q.slices_band_contrast[2],
            q.slices_blockiness,
        );
    }
    let a = quality.map(|q| q.exemplar_anisotropy);
    println!(
        "gradient anisotropy (u - v)/(u + v): exemplars {:+.3} / {:+.3} / {:+.3}, slices x / y / z {:+.3} / {:+.3} / {:+.3}; every volume has x - y + z = 0, so no volume comes closer than {:.3} on every axis (docs/solid.md)",
        a[0],
        a[1],
        a[2],
        quality[0].anisotropy,
        quality[1].anisotropy,
        quality[2].anisotropy,
        reachable_gap(a),
    );
    println!(
        "diagonal correlation J_uv / sqrt(J_uu J_vv): exemplars {:+.3} / {:+.3} / {:+.3}, slices x / y / z {:+.3} / {:+.3} / {:+.3} (a negative sign in all three roles has no consistent volume; docs/solid.md, \"Diagonal orientation\")",
        quality[0].exemplar_diagonal,
        quality[1].exemplar_diagonal,
        quality[2].exemplar_diagonal,
        quality[0].diagonal,
        quality[1].diagonal,
        quality[2].diagonal,
    );
    println!(
        "wrote {} and its slices ({}, ...)",
        args.output.display(),
        sibling(&args.output, "x").display()
    );
    Ok(())
}
