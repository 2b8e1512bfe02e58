//! `lazysolid bench hash`: the coherent hash against the random-probe and cuckoo hashes, a
//! dense array (the practical limit) and CPU hashbrown on 2 threads, following the GPU hash
//! literature's conventions (BGHT, cuCollections): insert and query rates in Mkeys/s versus
//! load factor, queries with 100 / 50 / 0 % present keys, sorted versus shuffled access, and the
//! key layouts; plus the figures of the coherent hashing paper (thesis Figs. 4.15–4.17).

pub(super) mod datasets;
mod figures;

use super::harness::{time_cpu, time_gpu, Bench, Throughput};
use super::CommonArgs;
use crate::cli::resolution::Resolution;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::{Args, ValueEnum};
use datasets::Dataset;
use lazysolid_compute::gpu::{Gpu, GpuBuffer};
use lazysolid_compute::hash::*;
use lazysolid_compute::shader_constants::HASH_NOT_FOUND;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rayon::prelude::*;
use std::sync::Arc;

/// The key sets of the sweep.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HashDataset {
    /// Uniformly random points of a 2D universe (the paper's 1M keys in 8K²).
    #[value(name = "random-2d")]
    Random2d,
    /// The mesh rasterized: coherent 2D keys (the key layouts and table pictures use it).
    Image,
    /// The mesh's surface voxels: coherent 3D keys.
    Voxels,
}

/// The hash schemes under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HashScheme {
    /// Robin Hood hashing with coherent probing.
    Coherent,
    /// Robin Hood hashing with random probing.
    Random,
    /// Cuckoo hashing.
    Cuckoo,
}

/// The command-line name of a value, which the suite also uses in its tables.
fn value_name(v: &impl ValueEnum) -> String {
    v.to_possible_value()
        .map(|p| p.get_name().to_string())
        .unwrap_or_default()
}

/// Sizes and sweeps of the hash benchmark.
#[derive(Args)]
pub struct HashArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Load factors of the sweep.
    #[arg(long, value_delimiter = ',', default_value = "0.5,0.7,0.85,0.95,0.99")]
    pub load_factors: Vec<f64>,
    /// Pixels of the image dataset (the mesh rasterized; square: N or NxN).
    #[arg(long, value_name = "WxH", default_value = "4096x4096")]
    pub image_res: Resolution,
    /// Side of the random dataset's 2D universe.
    #[arg(long, default_value_t = 8192)]
    pub random_universe: u32,
    /// Keys of the random dataset.
    #[arg(long, default_value_t = 1 << 20)]
    pub random_keys: usize,
    /// Side N of the voxel dataset's N³ grid.
    #[arg(long, value_name = "N", default_value_t = 512)]
    pub voxel_res: u32,
    /// The mesh of the image and voxel datasets: a name in the assets' meshes (armadillo,
    /// bunny00, ...) or a path to an OFF or OBJ file.
    #[arg(long, value_name = "NAME|PATH", default_value = "armadillo")]
    pub mesh: String,
    /// Datasets to run (the key-layout comparison needs `image`, the age histogram
    /// `random-2d`): a subset is a quick look at one case.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "random-2d,image,voxels"
    )]
    pub datasets: Vec<HashDataset>,
    /// Hash schemes to run (the baselines, dense array and hashbrown, always run).
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "coherent,random,cuckoo"
    )]
    pub schemes: Vec<HashScheme>,
    /// Small sizes (1024² image, 128³ voxels, 2^16 random keys): a quick look, not the
    /// reference measurement.
    #[arg(long)]
    pub quick: bool,
}

/// Query sets: (name, share of present keys, shuffled).
const QUERY_SETS: [(&str, u32, bool); 4] = [
    ("sorted 100%", 100, false),
    ("shuffled 100%", 100, true),
    ("sorted 50%", 50, false),
    ("sorted 0%", 0, false),
];

struct Uploaded {
    keys: GpuBuffer<u64>,
    payloads: GpuBuffer<u32>,
    queries: Vec<(String, GpuBuffer<u64>, Vec<u32>)>,
    results: GpuBuffer<u32>,
    n: usize,
}

fn query_sets(ds: &Dataset, u: &Universe) -> Vec<(String, Vec<u64>, Vec<u32>)> {
    let n = ds.points.len();
    let raster = |p: &[u32; 3]| {
        p[0] as u64 + ds.dims[0] as u64 * (p[1] as u64 + ds.dims[1] as u64 * p[2] as u64)
    };
    QUERY_SETS
        .iter()
        .map(|&(name, share, shuffled)| {
            let mut set: Vec<([u32; 3], u32)> = match share {
                100 => ds
                    .points
                    .iter()
                    .copied()
                    .zip(ds.payloads.iter().copied())
                    .collect(),
                0 => ds.absent.iter().map(|&p| (p, HASH_NOT_FOUND)).collect(),
                _ => (0..n)
                    .map(|i| {
                        if i % 2 == 0 {
                            (ds.points[i], ds.payloads[i])
                        } else {
                            (ds.absent[i], HASH_NOT_FOUND)
                        }
                    })
                    .collect(),
            };
            if share != 100 && share != 0 {
                set.sort_by_key(|(p, _)| raster(p));
            }
            if shuffled {
                set.shuffle(&mut rand_pcg::Pcg64Mcg::seed_from_u64(99));
            }
            (
                name.to_string(),
                set.iter().map(|(p, _)| u.key(*p)).collect(),
                set.iter().map(|e| e.1).collect(),
            )
        })
        .collect()
}

fn upload(gpu: &Gpu, ds: &Dataset, u: &Universe) -> anyhow::Result<Uploaded> {
    let keys: Vec<u64> = ds.points.iter().map(|&p| u.key(p)).collect();
    let mut queries = Vec::new();
    for (name, q, expected) in query_sets(ds, u) {
        queries.push((
            name,
            GpuBuffer::from_slice(gpu, "hash bench queries", &q)?,
            expected,
        ));
    }
    Ok(Uploaded {
        keys: GpuBuffer::from_slice(gpu, "hash bench keys", &keys)?,
        payloads: GpuBuffer::from_slice(gpu, "hash bench payloads", &ds.payloads)?,
        results: GpuBuffer::new(gpu, "hash bench results", keys.len())?,
        queries,
        n: keys.len(),
    })
}

/// A scheme under test.
enum Table {
    RobinHood(RobinHoodTable),
    Cuckoo(CuckooTable),
}

impl Table {
    fn record_query(
        &self,
        rec: &mut lazysolid_compute::gpu::Recorder<'_>,
        keys: &GpuBuffer<u64>,
        results: &GpuBuffer<u32>,
        n: usize,
    ) -> lazysolid_compute::gpu::GpuResult<()> {
        match self {
            Table::RobinHood(t) => t.record_query(rec, keys, results, n),
            Table::Cuckoo(t) => t.record_query(rec, keys, results, n),
        }
    }
}

const SCHEMES: [&str; 3] = ["coherent", "random", "cuckoo"];

fn build(
    kernels: &Arc<HashKernels>,
    u: Universe,
    up: &Uploaded,
    scheme: &str,
    lf: f64,
    validate: bool,
) -> Result<Table, HashError> {
    Ok(match scheme {
        "cuckoo" => Table::Cuckoo(CuckooTable::build(
            kernels,
            u,
            &up.keys,
            &up.payloads,
            up.n,
            CuckooConfig {
                load_factor: lf,
                validate,
                ..Default::default()
            },
        )?),
        probe => {
            let probe = if probe == "coherent" {
                Probe::Coherent
            } else {
                Probe::Random
            };
            let config = RobinHoodConfig {
                probe,
                load_factor: lf,
                max_load_factor: lf.max(0.99),
                grow: false,
                validate,
                histogram: false,
                ..Default::default()
            };
            Table::RobinHood(RobinHoodTable::build(
                kernels,
                u,
                &up.keys,
                &up.payloads,
                up.n,
                config,
            )?)
        }
    })
}

/// What the figures need from the sweep.
pub(crate) struct Sweep {
    pub dataset: String,
    pub rows: Vec<(String, f64, String, f64)>, // (scheme, lf, op, Mkeys/s at min)
    pub dense_sorted: f64,
    pub hashbrown_sorted: f64,
}

/// Runs the suite.
pub fn run(args: &HashArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    ensure!(
        args.load_factors.iter().all(|&lf| lf > 0.0 && lf <= 1.0),
        "--load-factors must lie in (0, 1]"
    );
    let image_side = args.image_res.side("--image-res", "the image dataset")?;
    let (image_size, voxel_res, random_keys, random_universe) = if args.quick {
        (1024, 128, 1 << 16, 2048)
    } else {
        (
            image_side,
            args.voxel_res,
            args.random_keys,
            args.random_universe,
        )
    };
    let wanted = |name: &str| args.datasets.iter().any(|d| value_name(d) == name);
    let schemes: Vec<&str> = SCHEMES
        .into_iter()
        .filter(|s| args.schemes.iter().any(|a| value_name(a) == *s))
        .collect();
    let mesh = if wanted("image") || wanted("voxels") {
        assets::mesh("--mesh", &args.mesh)?
    } else {
        Default::default()
    };
    let gpu = global.gpu()?;
    let kernels = HashKernels::new(&gpu)?;
    eprintln!("preparing datasets…");
    let mut datasets = Vec::new();
    if wanted("random-2d") {
        datasets.push(datasets::random_2d(random_universe, random_keys, 1));
    }
    if wanted("image") {
        datasets.push(datasets::armadillo_image(&mesh, image_size)?);
    }
    if wanted("voxels") {
        datasets.push(datasets::armadillo_voxels(&mesh, voxel_res)?);
    }
    let per_dataset = (args.load_factors.len() * schemes.len() * (1 + QUERY_SETS.len())
        + 2 * QUERY_SETS.len()) as u64;
    let mut bench = Bench::new(
        "bench-hash",
        &gpu,
        &args.common,
        per_dataset * datasets.len() as u64 + 6,
    )?;
    let figures_dir = bench.artifact_dir()?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    let mut notes: Vec<(String, f64)> = Vec::new();
    let mut sweeps = Vec::new();
    let mut table_pictures = Vec::new();

    for ds in &datasets {
        eprintln!("{}: {}", ds.name, ds.description);
        let layout = if ds.dimensions == 3 {
            KeyLayout::Morton
        } else {
            KeyLayout::RowMajor
        };
        let u = ds.universe(layout);
        let up = upload(&gpu, ds, &u)?;
        let n = up.n as u64;
        let mut sweep = Sweep {
            dataset: ds.name.clone(),
            rows: Vec::new(),
            dense_sorted: 0.0,
            hashbrown_sorted: 0.0,
        };

        // Baselines: the dense array and hashbrown on 2 threads, same queries.
        let dense = DenseTable::build(&kernels, u, &up.keys, &up.payloads, up.n)?;
        let map: hashbrown::HashMap<u64, u32> = ds
            .points
            .iter()
            .map(|&p| u.key(p))
            .zip(ds.payloads.iter().copied())
            .collect();
        for (name, q, expected) in &up.queries {
            let case = format!("{} query {name}", ds.name);
            let ms = bench.case(
                &case,
                n,
                "dense array (gpu)",
                Throughput::Elements,
                None,
                || time_gpu(&gpu, |rec| dense.record_query(rec, q, &up.results, up.n)),
            )?;
            ensure!(
                &up.results.read()? == expected,
                "{case}: the dense array answers wrongly"
            );
            let host_q = q.read()?;
            let mut out = vec![0u32; up.n];
            let hb_ms = bench.case(
                &case,
                n,
                "hashbrown (cpu, 2 threads)",
                Throughput::Elements,
                None,
                || {
                    Ok(time_cpu(|| {
                        pool.install(|| {
                            out.par_chunks_mut(1 << 16)
                                .zip(host_q.par_chunks(1 << 16))
                                .for_each(|(o, q)| {
                                    for (r, k) in o.iter_mut().zip(q) {
                                        *r = map.get(k).copied().unwrap_or(HASH_NOT_FOUND);
                                    }
                                })
                        })
                    })
                    .1)
                },
            )?;
            ensure!(&out == expected, "{case}: hashbrown answers wrongly");
            if name == "sorted 100%" {
                sweep.dense_sorted = n as f64 / ms / 1e3;
                sweep.hashbrown_sorted = n as f64 / hb_ms / 1e3;
            }
        }
        drop(dense);

        let mut validated = false;
        for &lf in &args.load_factors {
            for &scheme in &schemes {
                let mut table = match build(&kernels, u, &up, scheme, lf, !validated) {
                    Ok(t) => t,
                    Err(e @ (HashError::CuckooFailed { .. } | HashError::AgeOverflow { .. })) => {
                        eprintln!("{} lf {lf}: {scheme} does not build: {e}", ds.name);
                        notes.push((
                            format!("{} lf {lf}: {scheme} failed to build (1 = yes)", ds.name),
                            1.0,
                        ));
                        continue;
                    }
                    Err(e) => {
                        return Err(e).with_context(|| format!("{} lf {lf} {scheme}", ds.name))
                    }
                };
                validated = true;
                let baseline = (scheme == "coherent").then_some("random");
                let case = format!("{} lf {lf:.2} insert", ds.name);
                let timed =
                    bench.case(
                        &case,
                        n,
                        scheme,
                        Throughput::Elements,
                        baseline,
                        || match &mut table {
                            Table::RobinHood(t) => {
                                Ok(t.rebuild_timed(&up.keys, &up.payloads, up.n)?)
                            }
                            Table::Cuckoo(t) => Ok(t.rebuild_timed(
                                &up.keys,
                                &up.payloads,
                                up.n,
                                &CuckooConfig {
                                    load_factor: lf,
                                    ..Default::default()
                                },
                            )?),
                        },
                    );
                let ms = match timed {
                    Ok(ms) => ms,
                    Err(e) if scheme == "cuckoo" => {
                        eprintln!("{} lf {lf}: cuckoo rebuilds fail: {e:#}", ds.name);
                        notes.push((
                            format!("{} lf {lf}: {scheme} failed to build (1 = yes)", ds.name),
                            1.0,
                        ));
                        continue;
                    }
                    Err(e) => return Err(e),
                };
                sweep
                    .rows
                    .push((scheme.into(), lf, "insert".into(), n as f64 / ms / 1e3));
                if let Table::RobinHood(t) = &table {
                    notes.push((
                        format!("{} lf {lf:.2}: {scheme} max age", ds.name),
                        t.report.max_age as f64,
                    ));
                    if ds.name == "image" && ((lf - 0.99).abs() < 1e-9 || (lf - 0.85).abs() < 1e-9)
                    {
                        table_pictures.push((
                            format!("{scheme}-lf{lf:.2}"),
                            t.cells()?,
                            t.format(),
                            ds.dims[0],
                        ));
                    }
                }
                for (name, q, expected) in &up.queries {
                    let case = format!("{} lf {lf:.2} query {name}", ds.name);
                    let ms =
                        bench.case(&case, n, scheme, Throughput::Elements, baseline, || {
                            time_gpu(&gpu, |rec| table.record_query(rec, q, &up.results, up.n))
                        })?;
                    ensure!(
                        &up.results.read()? == expected,
                        "{case}: {scheme} answers wrongly"
                    );
                    sweep.rows.push((
                        scheme.into(),
                        lf,
                        format!("query {name}"),
                        n as f64 / ms / 1e3,
                    ));
                }
            }
        }
        sweeps.push(sweep);
    }

    // Key layouts on the image dataset at load factor 0.85, queries in raster order.
    let image = datasets.iter().find(|d| d.name == "image");
    for layout in KeyLayout::ALL.into_iter().filter(|_| image.is_some()) {
        let image = image.expect("filtered");
        let u = image.universe(layout);
        let up = upload(&gpu, image, &u)?;
        let (_, q, expected) = &up.queries[0];
        for scheme in schemes.iter().filter(|s| **s != "cuckoo") {
            let table = build(&kernels, u, &up, scheme, 0.85, false)?;
            let case = format!("image layout {} lf 0.85 query raster order", layout.name());
            let baseline = (*scheme == "coherent").then_some("random");
            bench.case(
                &case,
                up.n as u64,
                scheme,
                Throughput::Elements,
                baseline,
                || time_gpu(&gpu, |rec| table.record_query(rec, q, &up.results, up.n)),
            )?;
            ensure!(
                &up.results.read()? == expected,
                "{case}: {scheme} answers wrongly"
            );
        }
    }

    // Targets and headline ratios, from this run.
    let rows = bench.rows().to_vec();
    let rate = |case: &str, imp: &str| {
        rows.iter()
            .find(|r| r.case == case && r.implementation == imp)
            .map(|r| r.throughput)
            .unwrap_or(f64::NAN)
    };
    let q85 = "image lf 0.85 query sorted 100%";
    notes.push((
        "target: image lf 0.99 coherent max age (<= 15)".into(),
        notes
            .iter()
            .find(|(k, _)| k == "image lf 0.99: coherent max age")
            .map_or(f64::NAN, |v| v.1),
    ));
    notes.push((
        "target: image lf 0.85 sorted queries coherent / random (>= 4)".into(),
        rate(q85, "coherent") / rate(q85, "random"),
    ));
    notes.push((
        "target: image lf 0.85 sorted queries coherent / dense array (>= 0.5)".into(),
        rate(q85, "coherent") / rate("image query sorted 100%", "dense array (gpu)"),
    ));
    notes.push((
        "target: image lf 0.85 insertion coherent / random (>= 1.5)".into(),
        rate("image lf 0.85 insert", "coherent") / rate("image lf 0.85 insert", "random"),
    ));
    for ds in ["random-2d", "image", "voxels"] {
        for set in ["sorted 100%", "shuffled 100%"] {
            notes.push((
                format!("target: {ds} lf 0.85 {set} queries coherent / hashbrown 2 threads (> 1)"),
                rate(&format!("{ds} lf 0.85 query {set}"), "coherent")
                    / rate(&format!("{ds} query {set}"), "hashbrown (cpu, 2 threads)"),
            ));
        }
    }

    eprintln!("drawing figures…");
    figures::draw(
        &figures_dir,
        &kernels,
        datasets.iter().find(|d| d.name == "random-2d"),
        &sweeps,
        &table_pictures,
    )?;
    bench.finish(&notes)?;
    Ok(())
}
