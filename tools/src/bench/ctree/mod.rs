//! `lazysolid bench ctree`: compressed random-access trees (thesis §4.1.3) on smooth content
//! lazysolid makes itself and a photograph. Rate–distortion against BC1, BC4, BC7 and 2×2 block
//! VQ; Table 4.2 (level, nodes, scale, padding) and the topology's bytes per node where the tree
//! first matches BC1; device against host builds (byte-identical, timed); lookups of a 3D tree
//! against the four sparse stores over the same mesh, of a 2D tree against a plain MIP texture.

mod baselines;
mod images;
mod lookups;
mod rate;
mod report;

use super::harness::{time_cpu, Bench, Throughput};
use super::CommonArgs;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use images::TestImage;
use lazysolid_compute::ctree::{
    Border, CompressedTree, CtreeBuilder, CtreeOptions, DownloadedTree, ScalarField,
};
use lazysolid_renderer::mesh::Mesh;

/// Sizes of the compressed-tree benchmark.
#[derive(Args)]
pub struct CtreeArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Side of the terrain and the sky's width (texels).
    #[arg(long, default_value_t = 512)]
    pub size: u32,
    /// Side of the mesh's distance volume (voxels); its middle slice is a 2D test image.
    #[arg(long, default_value_t = 128)]
    pub volume: u32,
    /// The mesh of the distance field and of the sparse stores (asset name or path).
    #[arg(long, default_value = "bunny00")]
    pub mesh: String,
    /// The photograph (an exemplar asset name or path).
    #[arg(long, default_value = "stone33")]
    pub photo: String,
    /// Lookups per throughput case.
    #[arg(long, default_value_t = 1 << 20)]
    pub lookups: usize,
    /// Divide the sizes by 4 and the lookups by 16 (a quick look, not the reference run).
    #[arg(long)]
    pub quick: bool,
}

/// Runs the suite.
pub fn run(args: &CtreeArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    let div = if args.quick { 4 } else { 1 };
    let size = (args.size / div).max(16);
    let side = (args.volume / div).max(16);
    let lookups = (args.lookups / if args.quick { 16 } else { 1 }).max(1024);
    ensure!(size <= 4096, "--size {size}: at most 4096");
    ensure!(
        side <= 512,
        "--volume {side}: a 3D tree holds at most 513 per axis"
    );
    let gpu = global.gpu()?;
    let mesh_path = assets::mesh("--mesh", &args.mesh)?;
    let mesh = Mesh::load_unit_cube(&mesh_path)
        .with_context(|| format!("loading --mesh {}", mesh_path.display()))?;
    let mesh_name = mesh_path
        .file_stem()
        .unwrap_or_default()
        .to_string_lossy()
        .into_owned();
    let photo = assets::exemplar("--photo", &args.photo, None)?;
    let distance = images::distance_volume(&gpu, &mesh, side)?;
    let test_images: Vec<TestImage> = vec![
        images::terrain_image(size),
        images::distance_slice(&distance, side, &mesh_name),
        images::sky_image(size),
        images::photo_image(&photo)?,
    ];
    let cases = 2 * test_images.len() as u64 + 2 + 6;
    let mut bench = Bench::new("bench-ctree", &gpu, &args.common, cases)?;
    let dir = bench.artifact_dir()?;
    let mut notes = Vec::new();

    // Rate–distortion, Table 4.2 and topology costs.
    let steps = [
        0.5f32, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 24.0, 32.0, 48.0, 64.0,
    ];
    let mut measured = Vec::new();
    for img in &test_images {
        bench.status(format!("rate–distortion of {}", img.name));
        let rd = rate::measure(img, &steps)?;
        report::plot_rd(&dir, &rd)?;
        report::save_pictures(&dir, img, &rd)?;
        measured.push(rd);
    }
    report::write_rd(&dir, &measured, &mut notes)?;

    // Builds: the device against the host, byte-identical, at the step matching BC1.
    let mut builder = CtreeBuilder::new(&gpu)?;
    let volume_field = ScalarField::new(
        &format!("{mesh_name} distance volume"),
        3,
        [side; 3],
        distance
            .iter()
            .map(|&d| images::distance_grey(d, side as f32 / 4.0))
            .collect(),
    )?;
    let mut fields: Vec<(String, ScalarField, f32)> = Vec::new();
    for (img, rd) in test_images.iter().zip(&measured) {
        if img.channels == 1 {
            let values = img.texels.iter().map(|&g| g as f32).collect();
            let field = ScalarField::new(&img.name, 2, [img.width, img.height, 1], values)?;
            let step = rd.matches_bc1.as_ref().map_or(1.0, |p| p.step);
            fields.push((img.name.clone(), field, step));
        }
    }
    fields.push((
        format!("{mesh_name} distance volume {side}³"),
        volume_field.clone(),
        1.0,
    ));
    for (name, field, step) in &fields {
        let options = CtreeOptions {
            step: *step,
            ..Default::default()
        };
        let case = format!("build {name}, step {step}");
        let samples = field.samples() as u64;
        let mut cpu_tree = None;
        bench.case(
            &case,
            samples,
            "cpu (1 thread)",
            Throughput::Elements,
            None,
            || {
                let (tree, ms) = time_cpu(|| CompressedTree::build(field, &options));
                cpu_tree = Some(tree?);
                Ok(ms)
            },
        )?;
        let cpu_tree = cpu_tree.expect("measured at least once");
        let mut device = None;
        bench.case(
            &case,
            samples,
            "gpu builder (wall, with its readbacks)",
            Throughput::Elements,
            Some("cpu (1 thread)"),
            || {
                let (built, ms) = time_cpu(|| builder.build(field, &options));
                device = Some(built?);
                Ok(ms)
            },
        )?;
        let (device, report) = device.expect("measured at least once");
        ensure!(
            device.download()? == DownloadedTree::of(&cpu_tree),
            "{name}: the device build differs from the host build"
        );
        notes.push((
            format!("{name}: bytes (device = host)"),
            cpu_tree.size_bytes() as f64,
        ));
        // Ablation: the nodes past the samples coding nothing (Border::Free) instead of
        // anchoring the border, at the same step: bytes and the worst error of each.
        let free = CompressedTree::build(
            field,
            &CtreeOptions {
                border: Border::Free,
                ..options
            },
        )?;
        for (label, tree) in [("anchored", &cpu_tree), ("free", &free)] {
            let worst = tree
                .decode()
                .iter()
                .zip(&field.values)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0f32, f32::max);
            notes.push((
                format!("{name}: border {label}, bytes"),
                tree.size_bytes() as f64,
            ));
            notes.push((format!("{name}: border {label}, worst error"), worst as f64));
        }
        notes.push((
            format!("{name}: device submissions"),
            report.submissions as f64,
        ));
        let searched: u64 = report.candidates.iter().sum();
        notes.push((
            format!("{name}: candidate scales searched"),
            searched as f64,
        ));
    }

    // Lookups.
    let volume_tree = CompressedTree::build(&volume_field, &CtreeOptions::default())?;
    lookups::volume_against_stores(
        &gpu,
        &mut bench,
        &mesh,
        &volume_tree,
        &distance,
        side,
        lookups,
        &mut notes,
    )?;
    let terrain = &fields[0].1;
    let terrain_tree = CompressedTree::build(terrain, &CtreeOptions::default())?;
    lookups::image_against_mip(
        &gpu,
        &mut bench,
        terrain,
        &terrain_tree,
        lookups,
        &mut notes,
    )?;
    bench.finish(&notes)?;
    println!("figures and tables: {}", dir.display());
    Ok(())
}
