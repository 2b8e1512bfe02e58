//! `lazysolid bench textures`: thesis Table 4.1 on this machine. Every sparse texture
//! structure is built over the surface of a mesh at one equivalent resolution (the armadillo
//! at 1024³ by default) with the same procedural marble, then looked up at the surface points
//! one fixed 800×800 viewpoint sees. Per structure and filtering mode: the exact GPU bytes next
//! to the thesis' megabytes, the lookup time of the whole viewpoint (GPU timestamps around one
//! dispatch, warm-up then min/median), its speed relative to the octree of the same filtering
//! next to the thesis' ratio, and a picture of the viewpoint textured through the structure.

mod thesis;
mod viewpoint;

use super::harness::{time_cpu, Bench, Throughput};
use super::plot::{bar_chart, rgb_image};
use super::CommonArgs;
use crate::cli::builder::Builder;
use crate::cli::resolution::Resolution;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::{Args, ValueEnum};
use lazysolid_compute::hash::perfect::{PerfectAccess, PerfectConstruction};
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, Filter, HashStore, LookupMode, OctreeConfig, OctreeStore, PerfectStore,
    SparseStore, StoreKernels, TileTree, TileTreeConfig, TimedLookup,
};
use lazysolid_compute::voxel::{VoxelGrid, VoxelKeys, Voxelizer};
use lazysolid_renderer::mesh::Mesh;
use std::path::PathBuf;
use thesis::ThesisRow;
use viewpoint::Viewpoint;

/// The sparse texture structures of the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StoreKind {
    /// N³ tree textures (each shape of --octree).
    Octree,
    /// The coherent hash.
    Hash,
    /// The perfect spatial hash, one texel per key.
    Perfect,
    /// The blocked perfect hash (trilinear only: one block serves a trilinear footprint).
    PerfectBlocked,
    /// The TileTree.
    Tiletree,
}

/// The filtering modes of the lookups.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FilterKind {
    /// One texel per lookup.
    Nearest,
    /// Eight texels per lookup (the TileTree: bilinear on its tile).
    Trilinear,
}

impl From<FilterKind> for Filter {
    fn from(f: FilterKind) -> Filter {
        match f {
            FilterKind::Nearest => Filter::Nearest,
            FilterKind::Trilinear => Filter::Trilinear,
        }
    }
}

/// What to measure.
#[derive(Args)]
pub struct TexturesArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// The mesh: a name in the assets' meshes (armadillo, bunny00, ...) or a path to an OFF or
    /// OBJ file; normalized into the unit cube.
    #[arg(long, value_name = "NAME|PATH", default_value = "armadillo")]
    pub mesh: String,
    /// Equivalent resolution of every structure: the side N of an N³ grid over the unit cube.
    #[arg(long, value_name = "N", default_value_t = 1024)]
    pub voxel_res: u32,
    /// Pixels of the viewpoint (square: N or NxN).
    #[arg(long, value_name = "WxH", default_value = "800x800")]
    pub res: Resolution,
    /// Structures to measure.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "octree,hash,perfect,perfect-blocked,tiletree"
    )]
    pub stores: Vec<StoreKind>,
    /// Filtering modes to measure.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "nearest,trilinear"
    )]
    pub filters: Vec<FilterKind>,
    /// Where the perfect hash (texel layout) is constructed; the blocked layout is always
    /// built on the host.
    #[arg(long, value_enum, default_value_t = Builder::Auto)]
    pub builder: Builder,
    /// Seed of the marble colour source.
    #[arg(long, default_value_t = 7)]
    pub seed: u32,
    /// Octree shapes to measure, each as level sizes joined by '.', root first (e.g.
    /// 8.8.4.4); default: the store's choice for R, and all-4 and all-2 trees where they fit.
    #[arg(long, value_delimiter = ',')]
    pub octree: Vec<String>,
    /// Also time, on every trilinear (TileTree: bilinear) structure, the sample lookup a
    /// texture with `relief` reads: the filtered sum, the stored corners' weight and the
    /// gradient of the alpha byte, which carries the relief channel (0 extra bytes per texel).
    #[arg(long)]
    pub relief_lookups: bool,
}

/// One measured structure.
struct Measured {
    label: String,
    /// A few characters for the charts' axis.
    short: String,
    filter: Filter,
    thesis: Option<ThesisRow>,
    bytes: u64,
    /// Texels stored.
    texels: u64,
    build_ms: f64,
    lookup_ms: f64,
    /// The relief's sample lookup of the viewpoint (filtered structures, with --relief-lookups).
    relief_ms: Option<f64>,
    missing: usize,
}

/// Runs the suite.
pub fn run(args: &TexturesArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    args.res.check("--res", 16..=4096)?;
    let view_side = args.res.side("--res", "the viewpoint")?;
    let res = args.voxel_res;
    let wants = |s: StoreKind| args.stores.contains(&s);
    let filters: Vec<Filter> = [Filter::Nearest, Filter::Trilinear]
        .into_iter()
        .filter(|f| args.filters.iter().any(|&a| Filter::from(a) == *f))
        .collect();
    let octrees = if wants(StoreKind::Octree) {
        octree_configs(&args.octree, res)?
    } else {
        Vec::new()
    };
    let per_filter = octrees.len() as u64
        + [StoreKind::Hash, StoreKind::Perfect, StoreKind::Tiletree]
            .into_iter()
            .filter(|&s| wants(s))
            .count() as u64;
    let blocked = filters.contains(&Filter::Trilinear) && wants(StoreKind::PerfectBlocked);
    let cases = filters.len() as u64 * per_filter + blocked as u64;
    ensure!(
        cases > 0,
        "--stores and --filters leave nothing to measure (perfect-blocked has trilinear lookups \
         only)"
    );
    let mesh_path = assets::mesh("--mesh", &args.mesh)?;
    let mesh = Mesh::load_unit_cube(&mesh_path)
        .with_context(|| format!("loading --mesh {}", mesh_path.display()))?;
    let gpu = global.gpu()?;
    let construction = PerfectConstruction::from(args.builder).resolve(&gpu);
    let kernels = StoreKernels::new(&gpu)?;
    let mut voxelizer = Voxelizer::new(&gpu)?;
    let (surface, surface_ms) =
        time_cpu(|| voxelizer.surface(&mesh.positions, &mesh.triangles, res));
    let surface = surface.with_context(|| format!("voxelizing at --voxel-res {res}"))?;
    let (corners, corners_ms) =
        time_cpu(|| voxelizer.interpolation(&mesh.positions, &mesh.triangles, res));
    let corners = corners?;
    let cells = voxelizer.cells(&mesh.positions, &mesh.triangles, VoxelGrid::cells(res)?)?;
    let view = viewpoint::view(&mesh, view_side);
    ensure!(
        !view.points.is_empty(),
        "the viewpoint sees nothing of {}",
        mesh_path.display()
    );
    let bench = Bench::new("bench-textures", &gpu, &args.common, cases)?;
    let dir = bench.artifact_dir()?;
    let mut session = Session {
        bench,
        dir,
        view: &view,
        measured: Vec::new(),
        relief: args.relief_lookups,
    };
    let source = ColourSource::Marble { seed: args.seed };
    let octree_name = |c: &OctreeConfig| {
        c.levels
            .iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join("·")
    };
    // Ratios are to the first octree of the same filtering, when octrees are measured.
    let baseline = |f: Filter| {
        octrees
            .first()
            .map(|c| format!("octree {}", octree_name(c)) + descents(f))
    };
    let mut tree_notes = Vec::new();

    for filter in filters {
        let keys = match filter {
            Filter::Nearest => &surface,
            Filter::Trilinear => &corners,
        };
        for (i, config) in octrees.iter().enumerate() {
            let label = format!("octree {}", octree_name(config)) + descents(filter);
            let (store, build_ms) = build_octree(&kernels, res, keys, &source, config)?;
            // Nodes per level: what the memory of each tree shape is made of.
            for (level, n) in store.node_counts().into_iter().enumerate() {
                tree_notes.push((format!("{label} nodes at level {level}"), n as f64));
            }
            let thesis = (i == 0).then_some(match filter {
                Filter::Nearest => ThesisRow::OctreeNearest,
                Filter::Trilinear => ThesisRow::OctreeTrilinear,
            });
            let base = if i > 0 { baseline(filter) } else { None };
            session.measure(&store, filter, label, thesis, base, build_ms)?;
        }
        if wants(StoreKind::Hash) {
            let label = "coherent hash".to_string() + lookups(filter);
            let (store, build_ms) = time_cpu(|| {
                HashStore::build(&kernels, res, keys, &source, RobinHoodConfig::default())
            });
            let store = store.with_context(|| format!("building the {label}"))?;
            session.measure(&store, filter, label, None, baseline(filter), build_ms)?;
        }
        if wants(StoreKind::Perfect) {
            let label = "perfect hash".to_string() + lookups(filter);
            let (store, build_ms) = time_cpu(|| {
                PerfectStore::build_with(
                    &kernels,
                    res,
                    keys,
                    &source,
                    PerfectAccess::Constrained,
                    construction,
                )
            });
            let store = store.with_context(|| format!("building the {label}"))?;
            let thesis = match filter {
                Filter::Nearest => ThesisRow::HashNearest,
                Filter::Trilinear => ThesisRow::HashTrilinear,
            };
            session.measure(
                &store,
                filter,
                label,
                Some(thesis),
                baseline(filter),
                build_ms,
            )?;
            session.bench.set_builder(store.construction().name());
        }
        if filter == Filter::Trilinear && wants(StoreKind::PerfectBlocked) {
            let (store, build_ms) =
                time_cpu(|| PerfectStore::build_blocked(&kernels, res, &cells, &source, None));
            let store = store.context("building the blocked perfect hash")?;
            let label = format!(
                "perfect hash blocked, b = {} (1 block)",
                store.block().unwrap_or(0)
            );
            session.measure(
                &store,
                filter,
                label,
                Some(ThesisRow::HashBlocked),
                baseline(filter),
                build_ms,
            )?;
            session.bench.set_builder(store.construction().name());
        }
        if wants(StoreKind::Tiletree) {
            let label = "tiletree".to_string() + tile_filter(filter);
            let (tree, build_ms) = time_cpu(|| {
                TileTree::build(
                    &kernels,
                    &mesh.positions,
                    &mesh.triangles,
                    res,
                    &source,
                    TileTreeConfig::default(),
                )
            });
            let (tree, _) = tree.with_context(|| format!("building the {label}"))?;
            if filter == Filter::Trilinear {
                tree.write_tile_map_png(&session.dir.join("tiletree-tile-map.png"))?;
            }
            let thesis = (filter == Filter::Trilinear).then_some(ThesisRow::TileTree);
            session.measure(&tree, filter, label, thesis, baseline(filter), build_ms)?;
        }
    }

    let Session {
        bench,
        dir,
        measured,
        ..
    } = session;
    summary(&measured, &bench, &dir, args)?;
    let mut notes = vec![
        ("triangles".to_string(), mesh.triangles.len() as f64),
        ("resolution".to_string(), res as f64),
        ("surface voxels".to_string(), surface.len as f64),
        ("interpolation voxels".to_string(), corners.len as f64),
        ("surface voxelization ms".to_string(), surface_ms),
        ("interpolation voxelization ms".to_string(), corners_ms),
        (
            "viewpoint pixels".to_string(),
            (view_side * view_side) as f64,
        ),
        (
            "viewpoint surface points".to_string(),
            view.points.len() as f64,
        ),
    ];
    notes.extend(tree_notes);
    for m in &measured {
        notes.push((format!("{} bytes", m.label), m.bytes as f64));
        notes.push((format!("{} build ms", m.label), m.build_ms));
        notes.push((format!("{} points not stored", m.label), m.missing as f64));
    }
    bench.finish(&notes)?;
    Ok(())
}

fn descents(f: Filter) -> &'static str {
    match f {
        Filter::Nearest => " (nearest)",
        Filter::Trilinear => " (8 descents)",
    }
}

fn tile_filter(f: Filter) -> &'static str {
    match f {
        Filter::Nearest => " (nearest)",
        Filter::Trilinear => " (bilinear, 1 fetch)",
    }
}

fn lookups(f: Filter) -> &'static str {
    match f {
        Filter::Nearest => " (nearest)",
        Filter::Trilinear => " (8 lookups)",
    }
}

/// Octree shapes from `--octree`, or the defaults for `res`.
fn octree_configs(given: &[String], res: u32) -> anyhow::Result<Vec<OctreeConfig>> {
    let mut configs = Vec::new();
    if given.is_empty() {
        configs.push(OctreeConfig::for_resolution(res)?);
        for n in [4u32, 2] {
            let levels = (res as f64).log(n as f64).round() as u32;
            if n.checked_pow(levels) == Some(res) {
                let c = OctreeConfig {
                    levels: vec![n; levels as usize],
                    initial_pool_words: 1 << 16,
                };
                if c.check(res).is_ok() && !configs.contains(&c) {
                    configs.push(c);
                }
            }
        }
    } else {
        for text in given {
            let levels = text
                .split('.')
                .map(|n| {
                    n.parse::<u32>().with_context(|| {
                        format!("--octree {text:?}: level size {n:?} is not an integer")
                    })
                })
                .collect::<anyhow::Result<Vec<_>>>()?;
            let c = OctreeConfig {
                levels,
                initial_pool_words: 1 << 16,
            };
            c.check(res).with_context(|| format!("--octree {text:?}"))?;
            configs.push(c);
        }
    }
    Ok(configs)
}

/// Builds twice: the first build finds the pool size, the second allocates exactly that, as a
/// user who knows the surface would (the pool otherwise grows by doubling).
fn build_octree(
    kernels: &std::sync::Arc<StoreKernels>,
    res: u32,
    keys: &VoxelKeys,
    source: &ColourSource<'_>,
    config: &OctreeConfig,
) -> anyhow::Result<(OctreeStore, f64)> {
    let (first, _) = OctreeStore::build(kernels, res, keys, source, config.clone())?;
    let words = first.pool_words()?.len();
    drop(first);
    let sized = OctreeConfig {
        initial_pool_words: words,
        ..config.clone()
    };
    let (store, ms) = time_cpu(|| OctreeStore::build(kernels, res, keys, source, sized));
    Ok((store?.0, ms))
}

/// What every structure's measurement shares: the harness, the figures folder, the viewpoint
/// and the rows so far.
struct Session<'a> {
    bench: Bench,
    dir: PathBuf,
    view: &'a Viewpoint,
    measured: Vec<Measured>,
    /// Whether filtered structures also time the relief's sample lookup.
    relief: bool,
}

impl Session<'_> {
    /// Times the viewpoint's lookups through `store`, saves its picture, counts points that
    /// read an unstored texel.
    fn measure<S: SparseStore>(
        &mut self,
        store: &S,
        filter: Filter,
        label: String,
        thesis: Option<ThesisRow>,
        baseline: Option<String>,
        build_ms: f64,
    ) -> anyhow::Result<()> {
        let view = self.view;
        let lookup: TimedLookup<'_> = store.timed_lookup(&view.points, &view.normals, filter)?;
        let case = match filter {
            Filter::Nearest => "viewpoint lookups, nearest",
            Filter::Trilinear => "viewpoint lookups, trilinear",
        };
        let lookup_ms = self.bench.case(
            case,
            view.points.len() as u64,
            &label,
            Throughput::Elements,
            baseline.as_deref(),
            || Ok(lookup.run()?),
        )?;
        let colours = lookup.results()?;
        let missing = colours.iter().filter(|c| c.w == 0.0).count();
        let relief_ms = if self.relief && filter == Filter::Trilinear {
            let sample =
                store.timed_lookup_mode(&view.points, &view.normals, LookupMode::Sample)?;
            Some(self.bench.case(
                "viewpoint lookups, relief sample",
                view.points.len() as u64,
                &label,
                Throughput::Elements,
                None,
                || Ok(sample.run()?),
            )?)
        } else {
            None
        };
        let file = self.dir.join(format!("{}.png", slug(&label)));
        rgb_image(
            &file,
            view.size,
            view.size,
            viewpoint::picture(view, &colours),
        )?;
        self.measured.push(Measured {
            short: short_label(&label, filter),
            label,
            filter,
            thesis,
            bytes: store.bytes(),
            texels: store.len(),
            build_ms,
            lookup_ms,
            relief_ms,
            missing,
        });
        Ok(())
    }
}

/// "octree 8·8·4·4 (nearest)" → "oct 8844 N", "perfect hash blocked, b = 2 (1 block)" →
/// "psh b2 T": bars stay readable with a dozen structures.
fn short_label(label: &str, filter: Filter) -> String {
    let kind = if let Some(rest) = label.strip_prefix("octree ") {
        let digits: String = rest
            .split(' ')
            .next()
            .unwrap_or("")
            .chars()
            .filter(char::is_ascii_digit)
            .collect();
        // Trees of one level size read as N^levels (2^10), others by their digits (8844).
        match digits.chars().next() {
            Some(first) if digits.len() > 4 && digits.chars().all(|c| c == first) => {
                format!("oct {first}^{}", digits.len())
            }
            _ => format!("oct {digits}"),
        }
    } else if label.starts_with("perfect hash blocked") {
        format!(
            "psh b{}",
            label
                .split("b = ")
                .nth(1)
                .and_then(|r| r.chars().next())
                .unwrap_or('?')
        )
    } else if label.starts_with("perfect hash") {
        "psh".to_string()
    } else if label.starts_with("coherent hash") {
        "cohash".to_string()
    } else if label.starts_with("tiletree") {
        "tile".to_string()
    } else {
        label.chars().take(8).collect()
    };
    match filter {
        Filter::Nearest => format!("{kind} N"),
        Filter::Trilinear => format!("{kind} T"),
    }
}

fn slug(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect::<String>()
        .split('-')
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("-")
}

/// Prints the Table 4.1 comparison and draws it.
fn summary(
    measured: &[Measured],
    bench: &Bench,
    dir: &std::path::Path,
    args: &TexturesArgs,
) -> anyhow::Result<()> {
    // The thesis measured the armadillo at 1024³; elsewhere its megabytes mean nothing here.
    let comparable = args.mesh == "armadillo" && args.voxel_res == 1024;
    let thesis_mb = |m: &Measured| m.thesis.filter(|_| comparable).map(|t| t.megabytes());
    let base_ms = |f: Filter| {
        measured
            .iter()
            .find(|m| m.filter == f && m.thesis.is_some_and(|t| t.baseline() == t))
            .map(|m| m.lookup_ms)
    };
    println!(
        "Table 4.1 on {} ({}), {} at {}³, {}×{} viewpoint:",
        bench.info.device,
        bench.info.driver,
        args.mesh,
        args.voxel_res,
        args.res.width,
        args.res.height
    );
    println!(
        "{:<34} {:>10} {:>8} {:>10} {:>8} {:>12} {:>10} {:>10} {:>10}",
        "structure",
        "MB",
        "B/texel",
        "thesis MB",
        "vs",
        "lookup ms",
        "speed",
        "thesis",
        "relief ms"
    );
    for m in measured {
        let speed = base_ms(m.filter).map(|b| b / m.lookup_ms);
        println!(
            "{:<34} {:>10.2} {:>8.2} {:>10} {:>8} {:>12.3} {:>10} {:>10} {:>10}",
            m.label,
            m.bytes as f64 / 1e6,
            m.bytes as f64 / m.texels.max(1) as f64,
            thesis_mb(m).map(|t| format!("{t:.1}")).unwrap_or_default(),
            thesis_mb(m)
                .map(|t| format!("{:+.0}%", (m.bytes as f64 / 1e6 / t - 1.0) * 100.0))
                .unwrap_or_default(),
            m.lookup_ms,
            speed.map(|s| format!("{s:.2}x")).unwrap_or_default(),
            m.thesis
                .map(|t| format!("{:.2}x", t.speedup()))
                .unwrap_or_default(),
            m.relief_ms.map(|r| format!("{r:.3}")).unwrap_or_default(),
        );
    }
    println!(
        "B/texel: the structure's bytes per stored texel (a relief channel adds none: it is the \
         texel's alpha byte); relief ms: the sample lookup a texture with relief reads (sum, \
         coverage and alpha gradient), with --relief-lookups"
    );
    for m in measured {
        if let Some(t) = m.thesis {
            println!("  {} stands for the thesis' {}", m.label, t.label());
        }
    }
    // Axis labels are short forms (N: nearest, T: trilinear or bilinear); the table names them.
    let labels: Vec<String> = measured.iter().map(|m| m.short.clone()).collect();
    bar_chart(
        &dir.join("textures-memory.png"),
        &format!("{} at {}³: GPU memory", args.mesh, args.voxel_res),
        "structure (N nearest, T trilinear; oct: octree level sizes, psh: perfect hash)",
        "MB",
        &labels,
        &[
            (
                "lazysolid".to_string(),
                measured.iter().map(|m| m.bytes as f64 / 1e6).collect(),
            ),
            (
                "thesis".to_string(),
                measured
                    .iter()
                    .map(|m| thesis_mb(m).unwrap_or(0.0))
                    .collect(),
            ),
        ],
        false,
    )?;
    bar_chart(
        &dir.join("textures-speed.png"),
        &format!(
            "{} at {}³, {}² viewpoint: lookup speed relative to the octree of the same filtering",
            args.mesh, args.voxel_res, args.res.width
        ),
        "structure (N nearest, T trilinear; oct: octree level sizes, psh: perfect hash)",
        "× octree",
        &labels,
        &[
            (
                format!("lazysolid on {}", bench.info.device),
                measured
                    .iter()
                    .map(|m| base_ms(m.filter).map_or(0.0, |b| b / m.lookup_ms))
                    .collect(),
            ),
            (
                "thesis".to_string(),
                measured
                    .iter()
                    .map(|m| m.thesis.map_or(0.0, |t| t.speedup()))
                    .collect(),
            ),
        ],
        false,
    )?;
    Ok(())
}
