//! `lazysolid bench psh`: perfect spatial hashing (Lefebvre and Hoppe 2006). Per dataset: the
//! offset table's bits per key and the total bytes, construction time of the sequential CPU
//! reference against the GPU construction (wall clock of each, keys already in memory on its
//! side, read-backs included), and query rates next to the coherent hash (Robin Hood, coherent
//! probing, load factor 0.85) and the dense array on the same keys. Also the blocked variant's
//! bytes for b = 1..4 on the armadillo's interpolation cells.
//!
//! Both constructions are always timed (their comparison is the suite's point); `--builder`
//! chooses whose table the queries read, as it chooses the construction everywhere else.

use super::harness::{time_cpu, time_gpu, Bench, Throughput};
use super::hash::datasets::{self, Dataset};
use super::plot::bar_chart;
use super::CommonArgs;
use crate::cli::builder::Builder;
use crate::cli::resolution::Resolution;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_compute::hash::perfect::*;
use lazysolid_compute::hash::*;
use std::collections::HashSet;

/// Sizes of the perfect-hash benchmark.
#[derive(Args)]
pub struct PshArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Side of the 2D random dataset's universe.
    #[arg(long, default_value_t = 1024)]
    pub random_universe: u32,
    /// Keys of the 2D random dataset (up to 65,536 keep 8-bit offsets).
    #[arg(long, default_value_t = 60_000)]
    pub random_keys: usize,
    /// Pixels of the image dataset (the mesh rasterized; square: N or NxN; 400x400 gives 62k
    /// pixels, within the 8-bit offset range).
    #[arg(long, value_name = "WxH", default_value = "400x400")]
    pub image_res: Resolution,
    /// Sides N of the voxel datasets' N³ grids, one dataset each (1024 gives 2.6M keys).
    #[arg(
        long,
        value_name = "N",
        value_delimiter = ',',
        default_value = "256,1024"
    )]
    pub voxel_res: Vec<u32>,
    /// Side N of the N³ grid of the blocked-variant report (interpolation cells of the mesh).
    #[arg(long, value_name = "N", default_value_t = 256)]
    pub blocked_voxel_res: u32,
    /// The mesh of the image and voxel datasets: a name in the assets' meshes (armadillo,
    /// bunny00, ...) or a path to an OFF or OBJ file.
    #[arg(long, value_name = "NAME|PATH", default_value = "armadillo")]
    pub mesh: String,
    /// Whose table the queries read: both constructions are timed regardless.
    #[arg(long, value_enum, default_value_t = Builder::Auto)]
    pub builder: Builder,
    /// Small sizes (2^14 random keys, 256² image, 128³ voxels): a quick look only.
    #[arg(long)]
    pub quick: bool,
}

/// Largest dense array measured (bytes): lavapipe's heap is 2 GiB.
const DENSE_LIMIT: u64 = 1 << 30;

/// Perfect on the keys and every payload found by the CPU lookup.
fn check(t: &PerfectHash, keys: &[u64], payloads: &[u32], what: &str) -> anyhow::Result<()> {
    let mut slots = HashSet::with_capacity(keys.len());
    for (&k, &p) in keys.iter().zip(payloads) {
        ensure!(
            slots.insert(t.slot(t.universe.point(k))),
            "{what}: key {k} shares a slot"
        );
        ensure!(t.lookup_key(k) == Some(p), "{what}: key {k} reads wrongly");
    }
    Ok(())
}

struct Summary {
    name: String,
    cpu_ms: f64,
    gpu_ms: f64,
    psh_mkeys: f64,
    coherent_mkeys: f64,
    dense_mkeys: f64,
}

/// Runs the suite.
pub fn run(args: &PshArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    let image_side = args.image_res.side("--image-res", "the image dataset")?;
    let (random_universe, random_keys, image_size, resolutions, blocked_res) = if args.quick {
        (512, 1 << 14, 256, vec![128], 64)
    } else {
        (
            args.random_universe,
            args.random_keys,
            image_side,
            args.voxel_res.clone(),
            args.blocked_voxel_res,
        )
    };
    let mesh_path = assets::mesh("--mesh", &args.mesh)?;
    let gpu = global.gpu()?;
    let kernels = PerfectKernels::new(&gpu)?;
    let hash_kernels = HashKernels::new(&gpu)?;
    let builder = PerfectBuilder::new(&kernels);
    let queried = PerfectConstruction::from(args.builder).resolve(&gpu);
    eprintln!("preparing datasets…");
    let mut sets: Vec<Dataset> = vec![
        datasets::random_2d(random_universe, random_keys, 1),
        datasets::armadillo_image(&mesh_path, image_size)?,
    ];
    for &r in &resolutions {
        let mut ds = datasets::armadillo_voxels(&mesh_path, r)?;
        ds.name = format!("voxels-{r}");
        sets.push(ds);
    }
    let mut bench = Bench::new("bench-psh", &gpu, &args.common, 5 * sets.len() as u64)?;
    let figures = bench.artifact_dir()?;
    let mut notes: Vec<(String, f64)> = Vec::new();
    let mut summaries = Vec::new();

    for ds in &sets {
        let layout = if ds.dimensions == 3 {
            KeyLayout::Morton
        } else {
            KeyLayout::RowMajor
        };
        let u = ds.universe(layout);
        let keys: Vec<u64> = ds.points.iter().map(|&p| u.key(p)).collect();
        let n = keys.len();
        eprintln!("{}: {} ({n} keys)", ds.name, ds.description);
        let config = PerfectConfig::default();

        // Construction: the sequential reference against the GPU, each from its own memory.
        let case = format!("{} build", ds.name);
        let mut cpu_table = None;
        let cpu_ms = bench.case(
            &case,
            n as u64,
            "cpu reference (1 thread)",
            Throughput::Elements,
            None,
            || {
                let (t, ms) = time_cpu(|| build_perfect_cpu(u, &keys, &ds.payloads, config));
                cpu_table = Some(t?);
                Ok(ms)
            },
        )?;
        bench.set_builder(PerfectConstruction::Cpu.name());
        let cpu_table = cpu_table.context("no CPU table")?;
        check(&cpu_table, &keys, &ds.payloads, &format!("{} CPU", ds.name))?;
        let key_buf = GpuBuffer::from_slice(&gpu, "psh bench keys", &keys)?;
        let payload_buf = GpuBuffer::from_slice(&gpu, "psh bench payloads", &ds.payloads)?;
        let mut gpu_table = None;
        let gpu_build_ms = bench.case(
            &case,
            n as u64,
            "gpu construction",
            Throughput::Elements,
            Some("cpu reference (1 thread)"),
            || {
                let (t, ms) = time_cpu(|| builder.build(u, &key_buf, &payload_buf, n, config));
                gpu_table = Some(t?);
                Ok(ms)
            },
        )?;
        bench.set_builder(PerfectConstruction::Gpu.name());
        let gpu_table = gpu_table.context("no GPU table")?;
        let gpu_host = gpu_table.to_host()?;
        check(&gpu_host, &keys, &ds.payloads, &format!("{} GPU", ds.name))?;
        let s = cpu_table.sizes;
        let g = gpu_host.sizes;
        let name = &ds.name;
        for (label, value) in [
            ("keys", n as f64),
            ("|H| per axis", s.h as f64),
            ("load factor", s.load_factor(n)),
            ("cpu |Phi| per axis", s.phi as f64),
            ("gpu |Phi| per axis", g.phi as f64),
            ("offset component bits", s.component_bits as f64),
            ("cpu Phi bits per key", cpu_table.bits_per_key()),
            ("gpu Phi bits per key", gpu_host.bits_per_key()),
            ("cpu growths", cpu_table.report.growths() as f64),
            ("gpu growths", gpu_host.report.growths() as f64),
            ("cpu total bytes (constrained)", cpu_table.bytes() as f64),
            ("gpu total bytes (constrained)", gpu_host.bytes() as f64),
            (
                "total bytes (unconstrained)",
                table_bytes(&g, PerfectAccess::Unconstrained, 1) as f64,
            ),
            ("gpu speed-up over cpu (min)", cpu_ms / gpu_build_ms),
        ] {
            notes.push((format!("{name}: {label}"), value));
        }
        for a in cpu_table
            .report
            .attempts
            .iter()
            .chain(&gpu_host.report.attempts)
        {
            if let Some(f) = &a.failure {
                eprintln!("{name}: attempt at {} failed: {f}", a.sizes.describe());
            }
        }

        // Queries: present keys in raster order, through the GLSL include, on the table of the
        // chosen construction.
        let table = match queried {
            PerfectConstruction::Cpu => PerfectHashGpu::upload(&kernels, &cpu_table)?,
            _ => gpu_table,
        };
        let results = GpuBuffer::<u32>::new(&gpu, "psh bench results", n)?;
        let case = format!("{name} query");
        let psh_ms = bench.case(
            &case,
            n as u64,
            "perfect hash (gpu)",
            Throughput::Elements,
            Some("coherent hash lf 0.85 (gpu)"),
            || time_gpu(&gpu, |rec| table.record_query(rec, &key_buf, &results, n)),
        )?;
        bench.set_builder(queried.name());
        ensure!(
            results.read()? == ds.payloads,
            "{case}: the perfect hash answers wrongly"
        );
        let coherent = RobinHoodTable::build(
            &hash_kernels,
            u,
            &key_buf,
            &payload_buf,
            n,
            RobinHoodConfig {
                load_factor: 0.85,
                ..Default::default()
            },
        )?;
        let coherent_ms = bench.case(
            &case,
            n as u64,
            "coherent hash lf 0.85 (gpu)",
            Throughput::Elements,
            None,
            || {
                time_gpu(&gpu, |rec| {
                    coherent.record_query(rec, &key_buf, &results, n)
                })
            },
        )?;
        ensure!(
            results.read()? == ds.payloads,
            "{case}: the coherent hash answers wrongly"
        );
        notes.push((
            format!("{name}: coherent hash bytes"),
            coherent.bytes() as f64,
        ));
        drop(coherent);
        let mut dense_mkeys = 0.0;
        if u.key_count() * 4 <= DENSE_LIMIT {
            let dense = DenseTable::build(&hash_kernels, u, &key_buf, &payload_buf, n)?;
            let ms = bench.case(
                &case,
                n as u64,
                "dense array (gpu)",
                Throughput::Elements,
                None,
                || time_gpu(&gpu, |rec| dense.record_query(rec, &key_buf, &results, n)),
            )?;
            ensure!(
                results.read()? == ds.payloads,
                "{case}: the dense array answers wrongly"
            );
            notes.push((format!("{name}: dense array bytes"), dense.bytes() as f64));
            dense_mkeys = n as f64 / ms / 1e3;
        }
        summaries.push(Summary {
            name: name.clone(),
            cpu_ms,
            gpu_ms: gpu_build_ms,
            psh_mkeys: n as f64 / psh_ms / 1e3,
            coherent_mkeys: n as f64 / coherent_ms / 1e3,
            dense_mkeys,
        });
    }

    // The blocked variant: bytes for every block size on the armadillo's interpolation cells.
    let mesh = lazysolid_renderer::mesh::Mesh::load_unit_cube(&mesh_path)
        .with_context(|| format!("loading {}", mesh_path.display()))?;
    let cells = lazysolid_compute::voxel::grid_cells_cpu(
        &mesh.positions,
        &mesh.triangles,
        lazysolid_compute::voxel::VoxelGrid::cells(blocked_res)?,
    );
    notes.push((
        format!("blocked R={blocked_res}: interpolation cells"),
        cells.len() as f64,
    ));
    let texels = lazysolid_compute::voxel::dilate_cells_cpu(&cells, blocked_res).len();
    notes.push((
        format!("blocked R={blocked_res}: interpolation voxels"),
        texels as f64,
    ));
    let choices = blocked_sizes(&cells, blocked_res)?;
    for c in &choices {
        notes.push((
            format!("blocked R={blocked_res} b={}: blocks", c.block),
            c.blocks as f64,
        ));
        notes.push((
            format!("blocked R={blocked_res} b={}: bytes", c.block),
            c.bytes as f64,
        ));
    }
    let best = choices
        .iter()
        .min_by_key(|c| c.bytes)
        .context("no block size")?;
    notes.push((
        format!("blocked R={blocked_res}: chosen b"),
        best.block as f64,
    ));

    let categories: Vec<String> = summaries.iter().map(|s| s.name.clone()).collect();
    bar_chart(
        &figures.join("psh-construction.png"),
        "perfect hash construction (wall clock, min)",
        "dataset",
        "ms",
        &categories,
        &[
            (
                "cpu reference (1 thread)".into(),
                summaries.iter().map(|s| s.cpu_ms).collect(),
            ),
            (
                "gpu construction".into(),
                summaries.iter().map(|s| s.gpu_ms).collect(),
            ),
        ],
        true,
    )?;
    bar_chart(
        &figures.join("psh-queries.png"),
        "queries of present keys (GPU timestamps, min)",
        "dataset",
        "Mkeys/s",
        &categories,
        &[
            (
                "perfect hash".into(),
                summaries.iter().map(|s| s.psh_mkeys).collect(),
            ),
            (
                "coherent hash lf 0.85".into(),
                summaries.iter().map(|s| s.coherent_mkeys).collect(),
            ),
            (
                "dense array".into(),
                summaries.iter().map(|s| s.dense_mkeys).collect(),
            ),
        ],
        true,
    )?;
    bar_chart(
        &figures.join("psh-blocked-bytes.png"),
        &format!("blocked perfect hash, armadillo R={blocked_res}: bytes per block size"),
        "b",
        "MB",
        &choices
            .iter()
            .map(|c| format!("b={}", c.block))
            .collect::<Vec<_>>(),
        &[(
            "total".into(),
            choices.iter().map(|c| c.bytes as f64 / 1e6).collect(),
        )],
        false,
    )?;
    bench.finish(&notes)?;
    Ok(())
}
