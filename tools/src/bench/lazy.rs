//! `lazysolid bench lazy`: lazy solid synthesis around mesh surfaces (thesis 003 lines
//! 1083–1096). Per mesh and equivalent resolution R: the interpolation voxels of the surface
//! (what trilinear lookups read) are requested from a fresh lazy state; the table gives the
//! request's wall time (dependency walk, synthesis, read-back) and its device time, and the
//! notes the voxels needed and computed per level, their share of R³, the kept state's bytes
//! and the full volume's, next to the thesis' figures.

use super::harness::{time_cpu, Bench, Throughput};
use super::plot::rgb_image;
use super::CommonArgs;
use crate::cli::assets::ExemplarDir;
use crate::cli::tuning::SolidOrder;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use lazysolid_compute::gpu::{Gpu, GpuBuffer, Submissions};
use lazysolid_compute::hash::morton_decode;
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, HashStore, OctreeConfig, OctreeStore, PerfectStore, SparseStore, StoreKernels,
    TileTree, TileTreeConfig,
};
use lazysolid_compute::voxel::{VoxelKeys, Voxelizer};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_synth::cache::DiskCache;
use lazysolid_synth::solid::lazy::{
    finest_growth_cpu, lazy_key, GpuLazySolid, LazyReport, MemoryPolicy,
};
use lazysolid_synth::solid::{
    pack_rgb, voxel_colour, LevelSchedule, PreparedSolid, SolidRecipe, SolidSchedule,
};
use std::cell::RefCell;

/// What to measure.
#[derive(Args)]
pub struct LazyArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Meshes: names in the assets' meshes or paths to OFF or OBJ files; each is normalized
    /// into the unit cube.
    #[arg(
        long,
        value_name = "NAME|PATH",
        value_delimiter = ',',
        default_value = "armadillo,bunny00,ChineseDragon-10kv"
    )]
    pub meshes: Vec<String>,
    /// Equivalent resolutions R (the texture is R³ voxels over the unit cube).
    #[arg(
        long,
        value_name = "N",
        value_delimiter = ',',
        default_value = "256,512,1024"
    )]
    pub voxel_res: Vec<u32>,
    #[command(flatten)]
    pub exemplar: SolidExemplarArg,
    /// Seed of the jitter.
    #[arg(long, default_value_t = 3)]
    pub seed: u32,
    /// Only the first mesh at the first resolution.
    #[arg(long)]
    pub quick: bool,
    /// What the synthesis state keeps between requests: "keep" (every version) or a budget
    /// of whole levels, coarsest to second finest and then the finest, such as "48MB"
    /// [default: the synthesizer's].
    #[arg(long, value_name = "keep|NMB")]
    pub memory: Option<MemoryPolicy>,
    #[command(flatten)]
    pub order: SolidOrder,
    /// Resolution of the cross-section figure (a fresh state holding the surface, then the
    /// mid-z plane inside the mesh) [default: the first of --voxel-res]. It costs a second
    /// surface request, so a large run may want a small one.
    #[arg(long, value_name = "N")]
    pub section_res: Option<u32>,
    /// Also profile the first mesh's request at the first resolution: once per cumulative part
    /// of the correction, on a fresh state keeping every version, each dispatch timed on its
    /// own (`docs/lazy.md`, "Where the device time goes").
    #[arg(long)]
    pub profile_correction: bool,
}

/// The exemplar of the lazy suites (`lazy`, `cuts`): one image playing all three roles.
#[derive(Args)]
pub struct SolidExemplarArg {
    /// The exemplar playing every role: a name in the assets' exemplars or a path.
    #[arg(long, default_value = "terra")]
    pub exemplar: String,
    #[command(flatten)]
    pub exemplar_dir: ExemplarDir,
}

impl SolidExemplarArg {
    /// The recipe of the suite's solid texture: the exemplar playing every role, `seed`, and
    /// the defaults of `lazysolid solid` for everything else.
    pub fn recipe(&self, seed: u32) -> anyhow::Result<SolidRecipe> {
        let path = assets::exemplar(
            "--exemplar",
            &self.exemplar,
            self.exemplar_dir.path.as_deref(),
        )?;
        Ok(SolidRecipe {
            seed,
            ..SolidRecipe::new(path)
        })
    }
}

/// Prepares `recipe` (exemplars, analysis, candidates through the user's cache), printing how
/// the exemplar was fitted and oriented.
pub fn prepare(gpu: &Gpu, recipe: &SolidRecipe) -> anyhow::Result<PreparedSolid> {
    let sources = recipe
        .load()
        .with_context(|| format!("loading --exemplar {}", recipe.exemplar.display()))?;
    for fit in &sources.fits {
        println!("exemplar fit: {fit}");
    }
    println!("orientation: {}", sources.mirroring);
    let cache = DiskCache::user().ok();
    Ok(sources.prepare(gpu, cache.as_ref(), &mut |_, _| {})?)
}

/// Thesis figures for the same meshes at 1024³ (003 lines 1090–1096).
const THESIS: &str = "thesis (2008 GPU): 4.1 s (dragon) to 17 s, storage 17.1 to 54 MB, \
                      about 0.42 % of the 1024³ voxels synthesized";

/// Runs the suite.
pub fn run(args: &LazyArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    let (meshes, sizes) = if args.quick {
        (&args.meshes[..1], &args.voxel_res[..1])
    } else {
        (&args.meshes[..], &args.voxel_res[..])
    };
    ensure!(
        !meshes.is_empty() && !sizes.is_empty(),
        "--meshes and --voxel-res need a value"
    );
    for &r in sizes {
        ensure!(
            (16..=2048).contains(&r),
            "--voxel-res {r}: must lie in 16..=2048"
        );
    }
    let section_res = args.section_res.unwrap_or(sizes[0]);
    ensure!(
        (16..=2048).contains(&section_res),
        "--section-res {section_res}: must lie in 16..=2048"
    );
    let gpu = global.gpu()?;
    // Device time is the sum over every submission of a request, bracketed by timestamps.
    gpu.time_submissions(true);
    let recipe = SolidRecipe {
        schedule: SolidSchedule {
            parallel_levels: args.order.parallel_levels,
            ..SolidSchedule::default()
        },
        ..args.exemplar.recipe(args.seed)?
    };
    let prepared = prepare(&gpu, &recipe)?;
    let exemplars = prepared.exemplars();
    let state = |r: u32| {
        prepared
            .lazy(&gpu, r, args.memory.unwrap_or_default())
            .context("the lazy synthesis state")
    };
    let side = exemplars.side();
    let mut bench = Bench::new(
        "bench-lazy",
        &gpu,
        &args.common,
        (meshes.len() * sizes.len()) as u64,
    )?;
    let mut notes: Vec<(String, f64)> = vec![
        ("seed".into(), args.seed as f64),
        ("exemplar side".into(), side as f64),
    ];
    let dir = bench.artifact_dir()?;
    let mut voxelizer = Voxelizer::new(&gpu)?;
    for name in meshes {
        let mesh_path = assets::mesh("--meshes", name)?;
        let mesh = Mesh::load_unit_cube(&mesh_path)
            .with_context(|| format!("loading --meshes {}", mesh_path.display()))?;
        for &r in sizes {
            bench.status(format!("{name} {r}³: voxelizing"));
            let (keys, voxelize_ms) =
                time_cpu(|| voxelizer.interpolation(&mesh.positions, &mesh.triangles, r));
            let interp = keys?;
            let keys = interp.read()?;
            let requested: Vec<[i32; 3]> = keys
                .iter()
                .map(|&k| morton_decode(k, 3).map(|v| v as i32))
                .collect();
            type Last = (Vec<[u32; 3]>, LazyReport, GpuLazySolid, Submissions, f64);
            let last = RefCell::new(None::<Last>);
            let case = format!("{name} {r}³");
            bench.case(
                &case,
                requested.len() as u64,
                "gpu lazy (wall)",
                Throughput::Elements,
                None,
                || {
                    let mut lazy = state(r)?;
                    let before = gpu.submissions();
                    let (result, ms) = time_cpu(|| lazy.request(&requested));
                    let submissions = gpu.submissions().since(before);
                    let (triples, report) = result?;
                    *last.borrow_mut() = Some((triples, report, lazy, submissions, ms));
                    Ok(ms)
                },
            )?;
            let (triples, report, lazy, submissions, wall_ms) =
                last.into_inner().context("no measured run")?;
            if args.profile_correction && name == &meshes[0] && r == sizes[0] {
                bench.status(format!("{case}: correction profile"));
                super::correction_profile::run(&gpu, &|| state(r), &requested, &case, &mut notes)?;
            }
            let bytes = lazy.bytes();
            drop(lazy);
            bench.status(format!("{name} {r}³: filling the stores"));
            // The stores are filled with the request's colours: under a memory budget the
            // state has dropped its finest levels, and four more requests would recompute
            // them four times over.
            let colours: Vec<u32> = triples
                .iter()
                .map(|&t| pack_rgb(voxel_colour(exemplars, t)) | 0xff00_0000)
                .collect();
            drop(triples);
            let colours = GpuBuffer::from_slice(&gpu, "requested colours", &colours)?;
            let stores = store_bytes(&gpu, &interp, &colours, &mesh, r)?;
            drop(colours);
            let full = (r as f64).powi(3);
            let computed: u64 = report.computed.iter().sum();
            // Voxels synthesized (stored: upsampled, then corrected) and those of the
            // dependency sets read only as upsampled, computed in place by their readers.
            let finest = *report.upsampled.last().unwrap_or(&0) as f64;
            let finest_set = *report.needed.last().unwrap_or(&0) as f64;
            let add = |notes: &mut Vec<(String, f64)>, what: &str, v: f64| {
                notes.push((format!("{case}: {what}"), v));
            };
            add(&mut notes, "requested voxels", requested.len() as f64);
            add(
                &mut notes,
                "requested % of R³",
                100.0 * requested.len() as f64 / full,
            );
            add(
                &mut notes,
                "finest-level voxels synthesized % of R³",
                100.0 * finest / full,
            );
            add(
                &mut notes,
                "finest-level voxels synthesized / requested",
                finest / requested.len().max(1) as f64,
            );
            add(
                &mut notes,
                "finest-level voxels read as upsampled only",
                finest_set - finest,
            );
            add(
                &mut notes,
                "voxels synthesized, all levels",
                report.upsampled.iter().sum::<u64>() as f64,
            );
            add(
                &mut notes,
                "voxels in the dependency sets, all levels",
                report.needed.iter().sum::<u64>() as f64,
            );
            add(&mut notes, "voxel versions computed", computed as f64);
            for (store, b) in stores {
                add(&mut notes, &format!("store MB: {store}"), b as f64 / 1e6);
            }
            // The last run's wall time split by timestamps around every submission.
            add(&mut notes, "last run wall ms", wall_ms);
            add(
                &mut notes,
                "last run device ms, every submission",
                submissions.device_ms(),
            );
            add(
                &mut notes,
                "last run wall - device ms",
                wall_ms - submissions.device_ms(),
            );
            add(
                &mut notes,
                "host waits (submissions)",
                submissions.waits as f64,
            );
            add(
                &mut notes,
                "voxel versions per new voxel",
                computed as f64 / report.upsampled.iter().sum::<u64>().max(1) as f64,
            );
            add(&mut notes, "dependency walk ms", report.deps_ms);
            add(&mut notes, "synthesis device ms", report.gpu_ms);
            add(&mut notes, "kept state MB", bytes as f64 / 1e6);
            add(
                &mut notes,
                "peak state MB during the request",
                report.peak_state_bytes as f64 / 1e6,
            );
            add(&mut notes, "chunks", report.chunks as f64);
            // One per chunk, more when a set outgrew the walk's buffers.
            add(&mut notes, "dependency walks", report.walks as f64);
            add(
                &mut notes,
                "host waits per chunk",
                report.waits as f64 / report.chunks.max(1) as f64,
            );
            add(
                &mut notes,
                "device µs per voxel version",
                1e3 * report.gpu_ms / computed.max(1) as f64,
            );
            add(&mut notes, "full volume MB (RGB8)", full * 3.0 / 1e6);
            add(&mut notes, "voxelization ms", voxelize_ms);
            for (l, n) in report.upsampled.iter().enumerate() {
                add(
                    &mut notes,
                    &format!("level {l} voxels synthesized"),
                    *n as f64,
                );
            }
            // Where the finest level's voxels come from, per stage of the backward walk, for
            // one ordered pass and one parallel pass (on the host; up to 256³, where it takes
            // seconds).
            if r <= 256 {
                let keys: Vec<u64> = requested.iter().map(|&p| lazy_key(p)).collect();
                for (name, parallel) in [("ordered", false), ("parallel", true)] {
                    let schedule = LevelSchedule {
                        passes: 1,
                        parallel,
                    };
                    let (growth, upsampled) = finest_growth_cpu(&keys, schedule);
                    for (stage, added) in growth {
                        add(
                            &mut notes,
                            &format!("finest walk, one {name} pass: stage {stage} adds"),
                            added as f64,
                        );
                    }
                    add(
                        &mut notes,
                        &format!("finest walk, one {name} pass: needed only upsampled"),
                        upsampled as f64,
                    );
                }
            }
        }
        // The matter inside: the mid-z cross-section at --section-res, synthesized as a
        // second request into a state that already holds the surface.
        let r = section_res;
        bench.status(format!("{name} {r}³: cross-section"));
        let mut lazy = state(r)?;
        let keys = voxelizer
            .interpolation(&mesh.positions, &mesh.triangles, r)?
            .read()?;
        let surface: Vec<[i32; 3]> = keys
            .iter()
            .map(|&k| morton_decode(k, 3).map(|v| v as i32))
            .collect();
        lazy.request(&surface)?;
        let z = r / 2;
        let inside = section_mask(&mesh, r, z);
        let cut: Vec<[i32; 3]> = (0..r * r)
            .filter(|&i| inside[i as usize])
            .map(|i| [(i % r) as i32, (i / r) as i32, z as i32])
            .collect();
        let (triples, report) = lazy.request(&cut)?;
        let mut pixels = vec![40u8; (r * r * 3) as usize];
        for (p, t) in cut.iter().zip(&triples) {
            // Image rows top down: y up in the mesh.
            let row = r - 1 - p[1] as u32;
            let at = ((row * r + p[0] as u32) * 3) as usize;
            pixels[at..at + 3].copy_from_slice(&voxel_colour(exemplars, *t));
        }
        let stem = std::path::Path::new(name)
            .file_stem()
            .map_or(name.clone(), |s| s.to_string_lossy().into_owned());
        let path = dir.join(format!("{stem}-{r}-section-z{z}.png"));
        rgb_image(&path, r, r, pixels)?;
        let case = format!("{name} {r}³ cross-section z = {z}");
        notes.push((format!("{case}: voxels"), cut.len() as f64));
        notes.push((
            format!("{case}: voxel versions computed after the surface"),
            report.computed.iter().sum::<u64>() as f64,
        ));
        notes.push((format!("{case}: wall ms"), report.wall_ms));
    }
    println!("{THESIS}");
    bench.finish(&notes)?;
    Ok(())
}

/// Which voxels of the plane `z` (voxel centres, `r`² of them, x fastest) lie inside the closed
/// mesh: the parity of the surface crossings of the line along x through each row's centres.
fn section_mask(mesh: &Mesh, r: u32, z: u32) -> Vec<bool> {
    let zc = (z as f32 + 0.5) / r as f32;
    let mut rows: Vec<Vec<f32>> = vec![Vec::new(); r as usize];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let (lo, hi) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        if zc < a.z.min(b.z).min(c.z) || zc > a.z.max(b.z).max(c.z) {
            continue;
        }
        let first = ((lo * r as f32 - 0.5).ceil().max(0.0)) as u32;
        let last = ((hi * r as f32 - 0.5).floor().min(r as f32 - 1.0)) as i64;
        for y in first as i64..=last {
            let yc = (y as f32 + 0.5) / r as f32;
            // Barycentric coordinates of (yc, zc) in the triangle projected on the y-z plane.
            let d = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
            if d == 0.0 {
                continue;
            }
            let u = ((yc - a.y) * (c.z - a.z) - (c.y - a.y) * (zc - a.z)) / d;
            let v = ((b.y - a.y) * (zc - a.z) - (yc - a.y) * (b.z - a.z)) / d;
            if u >= 0.0 && v >= 0.0 && u + v < 1.0 {
                rows[y as usize].push(a.x + u * (b.x - a.x) + v * (c.x - a.x));
            }
        }
    }
    let mut mask = vec![false; (r * r) as usize];
    for (y, xs) in rows.iter_mut().enumerate() {
        xs.sort_by(f32::total_cmp);
        for x in 0..r {
            let xc = (x as f32 + 0.5) / r as f32;
            let crossings = xs.iter().take_while(|&&v| v < xc).count();
            mask[y * r as usize + x as usize] = crossings % 2 == 1;
        }
    }
    mask
}

/// Bytes of each store of the matter a request synthesized (`colours` of the interpolation
/// voxels `keys`, in key order): the coherent hash, the N³ tree and the perfect hash over the
/// interpolation voxels (trilinear reads), the TileTree over the mesh, whose texels' voxels the
/// stores look up among those keys (one missing is an error).
fn store_bytes(
    gpu: &Gpu,
    keys: &VoxelKeys,
    colours: &GpuBuffer<u32>,
    mesh: &Mesh,
    r: u32,
) -> anyhow::Result<Vec<(&'static str, u64)>> {
    let kernels = StoreKernels::new(gpu)?;
    let source = ColourSource::Buffer { keys, colours };
    let hash = HashStore::build(&kernels, r, keys, &source, RobinHoodConfig::default())?;
    let (octree, _) =
        OctreeStore::build(&kernels, r, keys, &source, OctreeConfig::for_resolution(r)?)?;
    let perfect = PerfectStore::build(&kernels, r, keys, &source, PerfectAccess::Constrained)?;
    let (tree, _) = TileTree::build(
        &kernels,
        &mesh.positions,
        &mesh.triangles,
        r,
        &source,
        TileTreeConfig::default(),
    )?;
    Ok(vec![
        ("coherent hash (trilinear)", hash.bytes()),
        ("octree (trilinear)", octree.bytes()),
        ("perfect hash (trilinear)", perfect.bytes()),
        ("tiletree", tree.bytes()),
    ])
}
