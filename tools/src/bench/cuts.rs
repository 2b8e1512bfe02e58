//! `lazysolid bench cuts`: new surface synthesized on demand (thesis 003 lines 1085 and
//! 1093–1096: each new 256² cut of the gargoyle in 8 ms on a 2008 GPU with 14.4 MB of
//! temporary memory). A lazy state and a coherent-hash store (nearest reads) first take the
//! mesh's outer surface; then each plane cut through the mesh (independent cuts of the whole
//! mesh) requests the surface voxels of its cap that the store lacks, synthesizes them and
//! inserts them — timed as one wall time, with its voxels, the state's growth and the store's.
//! A Voronoi fracture (each piece count from a fresh state holding the outer surface) is timed
//! the same way over the caps of all its pieces.
//!
//! A row's elements are the cut's cap triangles. New surface can be synthesized only once per
//! state, so every cut is measured once (the rows' min and median are that one time); one
//! unmeasured cut near the top of the mesh first compiles the kernels (lavapipe compiles at
//! first dispatch).

use super::harness::{time_cpu, Bench, Throughput};
use super::lazy::prepare;
use super::CommonArgs;
use crate::cli::{assets, GlobalArgs};
use anyhow::{anyhow, ensure, Context};
use clap::Args;
use glam::{DVec3, Vec3};
use lazysolid_compute::gpu::{Gpu, Submissions};
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::host_memory;
use lazysolid_compute::store::{HashStore, StoreKernels};
use lazysolid_compute::voxel::Voxelizer;
use lazysolid_renderer::fracture::{cut_pieces, fracture, random_sites, Fragment, Plane};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_synth::solid::lazy::{
    MatterColours, MatterSpec, MatterVoxels, MemoryPolicy, SharedLazy, StoredMatter,
};
use lazysolid_synth::solid::PreparedSolid;
use std::sync::{Arc, Mutex};

/// What to measure.
#[derive(Args)]
pub struct CutsArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// The mesh: a name in the assets' meshes or a path; normalized into the unit cube.
    #[arg(long, value_name = "NAME|PATH", default_value = "armadillo")]
    pub mesh: String,
    /// Equivalent resolutions R.
    #[arg(long, value_name = "N", value_delimiter = ',', default_value = "256")]
    pub voxel_res: Vec<u32>,
    /// Voronoi fractures to time, by piece count.
    #[arg(long, value_delimiter = ',', default_value = "8,32")]
    pub pieces: Vec<usize>,
    /// Times the plane cuts only, no fracture: each fracture starts from a fresh state that
    /// synthesizes the outer surface again, which at 1024³ takes minutes on lavapipe.
    #[arg(long)]
    pub no_fractures: bool,
    #[command(flatten)]
    pub exemplar: super::lazy::SolidExemplarArg,
    /// Seed of the jitter and of the fracture sites.
    #[arg(long, default_value_t = 3)]
    pub seed: u32,
    /// What the synthesis state keeps between requests: "keep" (every version) or a budget
    /// of whole levels, coarsest to second finest and then the finest, such as "48MB"
    /// [default: the synthesizer's]. Under a budget a cut recomputes the dropped levels it
    /// needs.
    #[arg(long, value_name = "keep|NMB")]
    pub memory: Option<MemoryPolicy>,
    /// Also time every dispatch of every cut by timestamps of its own and note the device
    /// time per kernel (the timestamps end each dispatch on its own, so wall and device times
    /// of a profiled run are a little longer than an unprofiled one's).
    #[arg(long)]
    pub profile_dispatches: bool,
}

/// The measured plane cuts through the centre of the unit cube: normals.
const CUTS: [[f64; 3]; 4] = [
    [0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.4],
];

/// Thesis figures (003 lines 1085, 1093–1096).
const THESIS: &str = "thesis (2008 GPU): 8 ms and 14.4 MB of temporary memory per new 256² cut; \
                      storage 1.3 MB for the equivalent of 256³";

/// Synthesized matter over the outer surface in a coherent-hash store: what every cut grows.
struct Holder {
    matter: StoredMatter<HashStore>,
    /// The matter's lazy state, for its per-level report of each cut.
    lazy: SharedLazy,
    gpu: Gpu,
}

/// What one cut or fracture asked and cost.
struct CutCost {
    cap_triangles: usize,
    cap_voxels: usize,
    new_voxels: usize,
    versions: u64,
    wall_ms: f64,
    /// Device time of the synthesis kernels alone (the lazy report's).
    synthesis_ms: f64,
    /// Per level, coarsest first: versions computed and voxels new to the state (the rest of
    /// the versions are corrections, and under a budget recomputations of dropped levels).
    levels: Vec<(u64, u64)>,
    /// The synthesis request's chunks, dependency walks and host waits (of the cut's).
    request: (u32, u32, u64),
    /// What the cut's submissions did: host waits, and device time from timestamps around
    /// every submission (the walk, sorts, synthesis, colours, inserts, copies).
    submissions: Submissions,
    state_growth: i64,
    request_bytes: u64,
    store_before: u64,
    store_after: u64,
    /// Device memory (every buffer) during the cut.
    device: Rise,
    /// Host heap during the cut (the dependency walk and the key lists run on the host).
    host: Rise,
}

/// Memory during a piece of work, measured: the most allocated above what was allocated
/// before it, and what stayed allocated after it (state and store growth; negative when the
/// memory policy dropped levels).
#[derive(Clone, Copy)]
struct Rise {
    peak: u64,
    kept: i64,
}

impl Rise {
    fn new(before: u64, live: u64, peak: u64) -> Rise {
        Rise {
            peak: peak.saturating_sub(before),
            kept: live as i64 - before as i64,
        }
    }

    /// The peak less what stayed: memory the work needed only while it ran.
    fn temporary(&self) -> u64 {
        self.peak.saturating_sub(self.kept.max(0) as u64)
    }
}

/// What every state of the suite is made from.
struct Setup<'a> {
    gpu: &'a Gpu,
    kernels: std::sync::Arc<StoreKernels>,
    prepared: &'a PreparedSolid,
    mesh: &'a Mesh,
    memory: Option<MemoryPolicy>,
}

impl Holder {
    /// A fresh state and store holding the outer surface at resolution `r`.
    fn new(setup: &Setup<'_>, voxelizer: &mut Voxelizer, r: u32) -> anyhow::Result<Holder> {
        let lazy = setup
            .prepared
            .lazy(setup.gpu, r, setup.memory.unwrap_or_default())
            .context("the lazy synthesis state")?;
        let mesh = setup.mesh;
        let lazy: SharedLazy = Arc::new(Mutex::new(lazy));
        let (matter, _) = StoredMatter::build(
            setup.gpu,
            voxelizer,
            MatterSpec {
                colours: MatterColours::Lazy(lazy.clone()),
                voxels: MatterVoxels::Surface,
                resolution: r,
            },
            &mesh.positions,
            &mesh.triangles,
            |keys, source| {
                let keys = keys.expect("surface voxels");
                HashStore::build(&setup.kernels, r, keys, source, RobinHoodConfig::default())
            },
        )?;
        Ok(Holder {
            matter,
            lazy,
            gpu: setup.gpu.clone(),
        })
    }

    /// Requests, synthesizes and inserts the surface voxels of `caps` the store lacks.
    fn cut(
        &mut self,
        voxelizer: &mut Voxelizer,
        caps: &(Vec<Vec3>, Vec<[u32; 3]>),
    ) -> anyhow::Result<CutCost> {
        let state_before = self.matter.state_bytes();
        let device_before = self.gpu.mark_memory();
        let host_before = host_memory::mark();
        let submissions_before = self.gpu.submissions();
        let (grown, wall_ms) = time_cpu(|| self.matter.grow(voxelizer, &caps.0, &caps.1));
        let submissions = self.gpu.submissions().since(submissions_before);
        let device = self.gpu.memory_use();
        let (host_live, host_peak) = (host_memory::live(), host_memory::peak());
        let grown = grown?;
        let synthesis = grown.synthesis;
        let (levels, request) = match synthesis {
            Some(_) => {
                let lazy = self.lazy.lock().unwrap_or_else(|p| p.into_inner());
                let report = lazy.last_report();
                let levels = report
                    .computed
                    .iter()
                    .zip(&report.upsampled)
                    .map(|(&c, &u)| (c, u))
                    .collect();
                (levels, (report.chunks, report.walks, report.waits))
            }
            None => (Vec::new(), (0, 0, 0)),
        };
        Ok(CutCost {
            cap_triangles: caps.1.len(),
            cap_voxels: grown.requested_voxels as usize,
            new_voxels: grown.new_voxels as usize,
            versions: synthesis.map_or(0, |s| s.versions),
            wall_ms,
            synthesis_ms: synthesis.map_or(0.0, |s| s.gpu_ms),
            levels,
            request,
            submissions,
            state_growth: self.matter.state_bytes() as i64 - state_before as i64,
            // The request's own buffers: keys (8 B) and colours (4 B) per new voxel.
            request_bytes: 12 * grown.new_voxels,
            store_before: grown.bytes_before,
            store_after: grown.bytes_after,
            device: Rise::new(device_before, device.live, device.peak),
            host: Rise::new(host_before, host_live, host_peak),
        })
    }
}

/// The cap faces of `pieces` as one triangle list. The two parts of a single cut share their
/// cap (reversed), so a cut passes only the part below.
fn caps(pieces: &[Fragment]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for p in pieces {
        let base = positions.len() as u32;
        positions.extend_from_slice(&p.positions);
        triangles.extend(p.triangles_of(true).map(|t| t.map(|v| v + base)));
    }
    (positions, triangles)
}

/// Runs the suite.
pub fn run(args: &CutsArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    for &r in &args.voxel_res {
        ensure!(
            (16..=2048).contains(&r),
            "--voxel-res {r}: must lie in 16..=2048"
        );
    }
    let gpu = global.gpu()?;
    // Device time is the sum over every submission of a cut, bracketed by timestamps.
    gpu.time_submissions(true);
    gpu.profile_dispatches(args.profile_dispatches);
    let prepared = prepare(&gpu, &args.exemplar.recipe(args.seed)?)?;
    let mesh_path = assets::mesh("--mesh", &args.mesh)?;
    let mesh = Mesh::load_unit_cube(&mesh_path)
        .with_context(|| format!("loading --mesh {}", mesh_path.display()))?;
    let setup = Setup {
        gpu: &gpu,
        kernels: StoreKernels::new(&gpu)?,
        prepared: &prepared,
        mesh: &mesh,
        memory: args.memory,
    };
    let mut voxelizer = Voxelizer::new(&gpu)?;
    // Each cut is new surface, measured once: the harness runs each case once, unwarmed (a
    // warm-up cut precedes the measured ones).
    let once = CommonArgs {
        warmup: 0,
        runs: 1,
        out_dir: args.common.out_dir.clone(),
    };
    // Three rows a cut: wall, device and the rest.
    let fractures: &[usize] = if args.no_fractures { &[] } else { &args.pieces };
    let cases = 3 * args.voxel_res.len() * (CUTS.len() + fractures.len());
    let mut bench = Bench::new("bench-cuts", &gpu, &once, cases as u64)?;
    let policy = args.memory.unwrap_or_default();
    println!("synthesis state memory policy: {policy}");
    let mut notes: Vec<(String, f64)> = vec![
        ("seed".into(), args.seed as f64),
        (
            "state budget MB (0: keep every version)".into(),
            match policy {
                MemoryPolicy::Keep => 0.0,
                MemoryPolicy::Budget(b) => b as f64 / 1e6,
            },
        ),
    ];
    let whole = Fragment::whole(&mesh);
    let bounds = mesh.bounds();
    let centre = ((bounds.min + bounds.max) * 0.5).as_dvec3();
    // Warm-up: a small cut near the top compiles every kernel a cut uses.
    let top = DVec3::new(centre.x, bounds.max.y as f64 - 0.03, centre.z);
    let (pieces, _) = cut_pieces(
        vec![whole.clone()],
        Plane::through(top, DVec3::Y),
        &mesh.source,
    )?;
    let warm_up = caps(&pieces[..1]);
    for &r in &args.voxel_res {
        bench.status(format!("{r}³: the outer surface"));
        let mut holder = Holder::new(&setup, &mut voxelizer, r)?;
        notes.push((
            format!("{r}³: outer surface voxels"),
            holder.matter.held().map_or(0, |k| k.len()) as f64,
        ));
        notes.push((
            format!("{r}³: state MB after the outer surface"),
            holder.matter.state_bytes() as f64 / 1e6,
        ));
        // Where the kept bytes are: what a budget keeps or drops is decided per level.
        {
            let lazy = holder
                .lazy
                .lock()
                .map_err(|_| anyhow!("lazy state poisoned"))?;
            for (l, (bytes, stored)) in lazy.level_bytes().iter().zip(lazy.stored()).enumerate() {
                notes.push((
                    format!("{r}³: level {l} state MB after the outer surface"),
                    *bytes as f64 / 1e6,
                ));
                notes.push((
                    format!("{r}³: level {l} voxels stored after the outer surface"),
                    stored as f64,
                ));
            }
        }
        holder.cut(&mut voxelizer, &warm_up)?;
        for (k, n) in CUTS.iter().enumerate() {
            let plane = Plane::through(centre, DVec3::from_array(*n));
            let (pieces, _) = cut_pieces(vec![whole.clone()], plane, &mesh.source)?;
            let case = format!("{r}³ plane cut {} normal {n:?}", k + 1);
            let cut = Measured {
                case: &case,
                cap: &caps(&pieces[..1]),
            };
            cut.run(&mut bench, &mut holder, &mut voxelizer, &mut notes)?;
        }
        for &n in fractures {
            let case = format!("{r}³ fracture {n} pieces");
            bench.status(format!("{case}: the outer surface"));
            let mut holder = Holder::new(&setup, &mut voxelizer, r)?;
            holder.cut(&mut voxelizer, &warm_up)?;
            let sites = random_sites(&mesh, n, args.seed as u64)?;
            let (pieces, fracture_ms) = time_cpu(|| fracture(&mesh, &sites));
            let pieces = pieces?;
            notes.push((format!("{case}: fracture geometry ms (CPU)"), fracture_ms));
            let cut = Measured {
                case: &case,
                cap: &caps(&pieces),
            };
            cut.run(&mut bench, &mut holder, &mut voxelizer, &mut notes)?;
        }
    }
    println!("{THESIS}");
    bench.finish(&notes)?;
    Ok(())
}

/// One measured cut: its row and its notes.
struct Measured<'a> {
    case: &'a str,
    cap: &'a (Vec<Vec3>, Vec<[u32; 3]>),
}

impl Measured<'_> {
    /// Times the cut once on `holder` as the case's row and notes what it cost.
    fn run(
        &self,
        bench: &mut Bench,
        holder: &mut Holder,
        voxelizer: &mut Voxelizer,
        notes: &mut Vec<(String, f64)>,
    ) -> anyhow::Result<()> {
        bench.status(self.case.to_string());
        let mut cost = None;
        holder.gpu.take_dispatch_profile();
        bench.case(
            self.case,
            self.cap.1.len() as u64,
            "lazy request + insert (wall)",
            Throughput::Elements,
            None,
            || {
                let c = holder.cut(voxelizer, self.cap)?;
                let ms = c.wall_ms;
                cost = Some(c);
                Ok(ms)
            },
        )?;
        let cost = cost.context("measured")?;
        // The same cut's device time and the rest, as rows beside its wall time.
        let device_ms = cost.submissions.device_ms();
        bench.case(
            self.case,
            self.cap.1.len() as u64,
            "device, every submission",
            Throughput::Elements,
            None,
            || Ok(device_ms),
        )?;
        bench.case(
            self.case,
            self.cap.1.len() as u64,
            "wall - device",
            Throughput::Elements,
            None,
            || Ok(cost.wall_ms - device_ms),
        )?;
        note_cost(notes, self.case, &cost);
        for k in holder.gpu.take_dispatch_profile() {
            let what = format!("{}: kernel {}", self.case, k.kernel);
            notes.push((format!("{what} device ms"), k.device_ns * 1e-6));
            notes.push((format!("{what} dispatches"), k.dispatches as f64));
        }
        Ok(())
    }
}

fn note_cost(notes: &mut Vec<(String, f64)>, case: &str, c: &CutCost) {
    let mut add = |what: &str, v: f64| notes.push((format!("{case}: {what}"), v));
    add("cap triangles", c.cap_triangles as f64);
    add("cap surface voxels", c.cap_voxels as f64);
    add("new voxels", c.new_voxels as f64);
    add("voxel versions synthesized", c.versions as f64);
    add(
        "voxel versions per new voxel",
        c.versions as f64 / c.new_voxels.max(1) as f64,
    );
    add("wall ms", c.wall_ms);
    add("device ms, every submission", c.submissions.device_ms());
    add(
        "wall - device ms (host work, allocation, waits)",
        c.wall_ms - c.submissions.device_ms(),
    );
    add(
        "wall - device % of wall",
        100.0 * (1.0 - c.submissions.device_ms() / c.wall_ms.max(1e-9)),
    );
    add("host waits (submissions)", c.submissions.waits as f64);
    let (chunks, walks, waits) = c.request;
    add("synthesis request chunks", chunks as f64);
    // One per chunk, more when a set outgrew the walk's buffers.
    add("synthesis request dependency walks", walks as f64);
    add("synthesis request host waits", waits as f64);
    add(
        "synthesis request host waits per chunk",
        waits as f64 / chunks.max(1) as f64,
    );
    add("synthesis kernels device ms", c.synthesis_ms);
    for (l, &(computed, new)) in c.levels.iter().enumerate() {
        add(&format!("level {l} versions computed"), computed as f64);
        add(&format!("level {l} voxels new to the state"), new as f64);
    }
    // Negative when the memory policy dropped levels the state held before the cut.
    add("kept state growth MB", c.state_growth as f64 / 1e6);
    add(
        "request buffers MB (keys + colours)",
        c.request_bytes as f64 / 1e6,
    );
    add("store MB before", c.store_before as f64 / 1e6);
    add("store MB after", c.store_after as f64 / 1e6);
    // Measured, see `Rise`.
    for (what, rise) in [("device", c.device), ("host heap", c.host)] {
        add(
            &format!("{what} MB at peak above before"),
            rise.peak as f64 / 1e6,
        );
        add(&format!("{what} MB kept after"), rise.kept as f64 / 1e6);
        add(
            &format!("{what} temporary MB (peak - kept)"),
            rise.temporary() as f64 / 1e6,
        );
    }
    add(
        "temporary MB, device + host",
        (c.device.temporary() + c.host.temporary()) as f64 / 1e6,
    );
}
