//! `lazysolid multiscale GRAPH.toml --level T --res WxH --offset X,Y -o out.png`: a window of
//! depth `T` of the unbounded multiscale texture an exemplar graph defines; and
//! `lazysolid zoom GRAPH.toml --from T0 --to T1 --frame-count N --out-dir DIR`: a zoom into a point, each
//! frame a window at a fractional depth (a blend of the two depths around it), as numbered PNGs
//! and an animated GIF. See docs/multiscale.md.

use super::assets::load_graph;
use super::components::components;
use super::output::write_png;
use super::output::{check_writable, check_writable_dir};
use super::resolution::Resolution;
use super::tuning::{Coherence, Schedule};
use super::GlobalArgs;
use anyhow::{ensure, Context};
use clap::Args;
use lazysolid_synth::multiscale::{
    analyze_graph, colour, synthesize_multiscale_cpu, ExemplarGraph, MultiscaleAnalysis,
    MultiscaleGpu, MultiscaleParams, MultiscaleSynthesis,
};
use lazysolid_synth::{AnalysisParams, Region};
use std::path::PathBuf;
use std::time::Instant;

/// Options shared by `multiscale` and `zoom`.
#[derive(Args)]
pub struct GraphOptions {
    /// The exemplar graph (TOML): [[exemplar]] name and image (asset name or path relative
    /// to the file), [[edge]] source, destination, r; root.
    #[arg(value_name = "GRAPH.toml")]
    pub graph: PathBuf,
    /// Seed of the jitter.
    #[arg(long, default_value_t = 1)]
    pub seed: u32,
    /// Synthesize with the CPU reference instead of the device.
    #[arg(long)]
    pub cpu: bool,
    #[command(flatten)]
    pub schedule: Schedule,
    #[command(flatten)]
    pub coherence: Coherence,
}

/// `lazysolid multiscale`.
#[derive(Args)]
pub struct MultiscaleArgs {
    /// Synthesis depth T (0: the root's coarsest level; the root's own texels at its L).
    #[arg(long)]
    pub level: u32,
    /// Output size WxH in pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "256x256")]
    pub res: Resolution,
    /// Absolute position X,Y of the first pixel in the plane of depth T.
    #[arg(long, default_value = "0,0", value_parser = parse_pair::<i32>, allow_hyphen_values = true)]
    pub offset: (i32, i32),
    /// The PNG to write; NAME.exemplars.png next to it shows which exemplar each pixel uses.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub graph: GraphOptions,
}

/// `lazysolid zoom`.
#[derive(Args)]
pub struct ZoomArgs {
    /// First depth (may be fractional).
    #[arg(long)]
    pub from: f64,
    /// Last depth.
    #[arg(long)]
    pub to: f64,
    /// Frames, evenly spaced in depth (a constant zoom speed).
    #[arg(long, value_name = "N", default_value_t = 32)]
    pub frame_count: u32,
    /// Frame size WxH in pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "192x192")]
    pub res: Resolution,
    /// The point zoomed into, X,Y in texels of depth 0.
    #[arg(long, default_value = "0.37,0.61", value_parser = parse_pair::<f64>, allow_hyphen_values = true)]
    pub center: (f64, f64),
    /// Frames per second of the GIF preview.
    #[arg(long, default_value_t = 12.0)]
    pub fps: f32,
    /// The folder for frame_NNNN.png and zoom.gif (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    #[command(flatten)]
    pub graph: GraphOptions,
}

fn parse_pair<T: std::str::FromStr>(s: &str) -> Result<(T, T), String> {
    components(s, "", "a number").map(|[x, y]| (x, y))
}

/// A graph analysed, with its analysis time.
pub struct Analysed {
    pub graph: ExemplarGraph,
    pub analysis: MultiscaleAnalysis,
    pub analysis_s: f64,
}

impl GraphOptions {
    /// Loads and analyses the graph.
    pub fn analyse(&self) -> anyhow::Result<Analysed> {
        let graph = load_graph(&self.graph)?;
        let start = Instant::now();
        let analysis = analyze_graph(
            &graph,
            &AnalysisParams {
                k: self.coherence.k,
                spread: self.coherence.spread,
                toroidal: true,
                // Ignored: the multiscale appearance space is colour only.
                feature_weight: 0,
                ..AnalysisParams::default()
            },
        )?;
        Ok(Analysed {
            graph,
            analysis,
            analysis_s: start.elapsed().as_secs_f64(),
        })
    }

    fn params(&self, depth: u32) -> anyhow::Result<MultiscaleParams> {
        Ok(MultiscaleParams::new(
            self.seed,
            depth,
            &self.schedule.passes,
            &self.schedule.jitter,
            self.coherence.period_penalty,
        )?)
    }
}

/// Synthesizes on the device or the CPU.
pub enum Engine {
    Gpu(MultiscaleGpu),
    Cpu,
}

impl Engine {
    fn new(cpu: bool, global: &GlobalArgs, analysis: &MultiscaleAnalysis) -> anyhow::Result<Self> {
        Ok(if cpu {
            Engine::Cpu
        } else {
            Engine::Gpu(MultiscaleGpu::new(&global.gpu()?, analysis)?)
        })
    }

    fn run(
        &self,
        analysis: &MultiscaleAnalysis,
        params: &MultiscaleParams,
        window: Region,
    ) -> anyhow::Result<MultiscaleSynthesis> {
        Ok(match self {
            Engine::Gpu(g) => g.synthesize(analysis, params, window, false)?.0,
            Engine::Cpu => synthesize_multiscale_cpu(analysis, params, window)?,
        })
    }
}

/// Distinct colours of the exemplar map.
const EXEMPLAR_COLOURS: [[u8; 3]; 8] = [
    [230, 25, 75],
    [60, 180, 75],
    [0, 130, 200],
    [255, 225, 25],
    [145, 30, 180],
    [70, 240, 240],
    [245, 130, 48],
    [128, 128, 128],
];

/// Runs `multiscale`.
pub fn run(args: &MultiscaleArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    ensure!(
        args.output
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png")),
        "-o {}: the output must be a .png file",
        args.output.display()
    );
    check_writable("-o", &args.output)?;
    let map_path = args.output.with_extension("exemplars.png");
    check_writable("-o", &map_path)?;
    let params = args.graph.params(args.level)?;
    let a = args.graph.analyse()?;
    let engine = Engine::new(args.graph.cpu, global, &a.analysis)?;
    let window = Region {
        origin: [args.offset.0, args.offset.1],
        size: [args.res.width, args.res.height],
    };
    let start = Instant::now();
    let out = engine.run(&a.analysis, &params, window)?;
    let synth_s = start.elapsed().as_secs_f64();
    let states = out.window_states();
    let colours: Vec<[u8; 3]> = states.iter().map(|s| colour(&a.analysis, s)).collect();
    let map: Vec<[u8; 3]> = states
        .iter()
        .map(|s| EXEMPLAR_COLOURS[s.exemplar() % EXEMPLAR_COLOURS.len()])
        .collect();
    write_png(&args.output, args.res.width, args.res.height, &colours)?;
    write_png(&map_path, args.res.width, args.res.height, &map)?;
    println!(
        "graph {} ({} exemplars, {} edges, {} distinct depth sets, loop from depth {})",
        args.graph.graph.display(),
        a.graph.names.len(),
        a.graph.topology.edges.len(),
        a.analysis.sets.len(),
        a.analysis.superexemplar.loop_start
    );
    println!(
        "depth {} window {}x{} at ({}, {}), seed {}",
        args.level, args.res.width, args.res.height, args.offset.0, args.offset.1, params.seed
    );
    println!("analysis (CPU)  {:8.3} s", a.analysis_s);
    println!(
        "synthesis ({}) {:8.3} s",
        if args.graph.cpu { "CPU" } else { "GPU" },
        synth_s
    );
    for (i, name) in a.graph.names.iter().enumerate() {
        let n = states.iter().filter(|s| s.exemplar() == i).count();
        let magnified = states
            .iter()
            .filter(|s| s.exemplar() == i && s.magnified())
            .count();
        println!(
            "  exemplar {name:12} {:5.1} % of pixels ({:.1} % magnified past its finest level)",
            100.0 * n as f64 / states.len() as f64,
            100.0 * magnified as f64 / states.len() as f64
        );
    }
    println!("wrote {} and {}", args.output.display(), map_path.display());
    Ok(())
}

/// A synthesized window of one depth, sampled in that depth's continuous plane.
struct Plane {
    origin: [i32; 2],
    size: [u32; 2],
    rgb: Vec<[f32; 3]>,
}

impl Plane {
    fn texel(&self, x: i32, y: i32) -> [f32; 3] {
        let lx = (x - self.origin[0]).clamp(0, self.size[0] as i32 - 1) as usize;
        let ly = (y - self.origin[1]).clamp(0, self.size[1] as i32 - 1) as usize;
        self.rgb[ly * self.size[0] as usize + lx]
    }

    /// Bilinear sample at continuous position (x, y) (texel centres at integer + ½).
    fn sample(&self, x: f64, y: f64) -> [f32; 3] {
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = ((fx - x0) as f32, (fy - y0) as f32);
        let (x0, y0) = (x0 as i32, y0 as i32);
        let (a, b, c, d) = (
            self.texel(x0, y0),
            self.texel(x0 + 1, y0),
            self.texel(x0, y0 + 1),
            self.texel(x0 + 1, y0 + 1),
        );
        std::array::from_fn(|i| {
            (a[i] * (1.0 - tx) + b[i] * tx) * (1.0 - ty) + (c[i] * (1.0 - tx) + d[i] * tx) * ty
        })
    }
}

/// Runs `zoom`.
pub fn run_zoom(args: &ZoomArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    ensure!(args.frame_count >= 1, "--frame-count must be at least 1");
    ensure!(
        args.from >= 0.0 && args.to >= 0.0,
        "--from and --to must not be negative"
    );
    check_writable_dir("--out-dir", &args.out_dir)?;
    std::fs::create_dir_all(&args.out_dir).with_context(|| {
        format!(
            "--out-dir {}: cannot create the folder",
            args.out_dir.display()
        )
    })?;
    let (w, h) = (args.res.width, args.res.height);
    let deepest = args.from.max(args.to).floor() as u32 + 1;
    args.graph.params(deepest)?;
    let a = args.graph.analyse()?;
    let engine = Engine::new(args.graph.cpu, global, &a.analysis)?;
    // One window per integer depth, covering the frame at every scale it serves: as the
    // coarser depth of a frame (magnified up to 2×) or the finer (shown at ½ to 1×).
    let shallowest = args.from.min(args.to).floor() as u32;
    let start = Instant::now();
    let mut planes = Vec::new();
    for d in shallowest..=deepest {
        let scale = (1u64 << d) as f64;
        let (cx, cy) = (args.center.0 * scale, args.center.1 * scale);
        let size = [2 * w + 8, 2 * h + 8];
        let origin = [
            (cx - size[0] as f64 / 2.0).floor() as i32,
            (cy - size[1] as f64 / 2.0).floor() as i32,
        ];
        let window = Region { origin, size };
        let params = args.graph.params(d)?;
        let out = engine.run(&a.analysis, &params, window)?;
        let rgb = out
            .window_states()
            .iter()
            .map(|s| colour(&a.analysis, s).map(f32::from))
            .collect();
        planes.push(Plane { origin, size, rgb });
    }
    let synth_s = start.elapsed().as_secs_f64();
    let mut gif = Vec::new();
    for f in 0..args.frame_count {
        let z = if args.frame_count == 1 {
            args.from
        } else {
            args.from + (args.to - args.from) * f as f64 / (args.frame_count - 1) as f64
        };
        let d = z.floor() as u32;
        let frac = z - d as f64;
        let coarse = &planes[(d - shallowest) as usize];
        let fine = &planes[(d + 1 - shallowest) as usize];
        let mut rgb = Vec::with_capacity((w * h) as usize);
        for y in 0..h {
            for x in 0..w {
                // Frame pixel → position in the plane of depth d (2^frac frame pixels per texel).
                let m = 2f64.powf(frac);
                let scale = (1u64 << d) as f64;
                let px = args.center.0 * scale + (x as f64 + 0.5 - w as f64 / 2.0) / m;
                let py = args.center.1 * scale + (y as f64 + 0.5 - h as f64 / 2.0) / m;
                let c0 = coarse.sample(px, py);
                // In depth d + 1 a frame pixel spans 2/m ≥ 1 texels: average 4 samples.
                let step = 0.5 / m;
                let mut c1 = [0.0f32; 3];
                for (ox, oy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
                    let s = fine.sample(2.0 * px + ox * step, 2.0 * py + oy * step);
                    for i in 0..3 {
                        c1[i] += s[i] / 4.0;
                    }
                }
                let t = frac as f32;
                rgb.push(std::array::from_fn(|i| {
                    (c0[i] * (1.0 - t) + c1[i] * t).round().clamp(0.0, 255.0) as u8
                }));
            }
        }
        let path = args.out_dir.join(format!("frame_{f:04}.png"));
        write_png(&path, w, h, &rgb)?;
        let rgba: Vec<u8> = rgb.iter().flat_map(|p| [p[0], p[1], p[2], 255]).collect();
        gif.push(image::RgbaImage::from_raw(w, h, rgba).expect("one RGBA word per pixel"));
    }
    let gif_path = args.out_dir.join("zoom.gif");
    lazysolid_renderer::output::write_gif(&gif_path, &gif, args.fps)?;
    println!(
        "graph {}: depths {}..={} synthesized in {:.3} s ({}), analysis {:.3} s",
        args.graph.graph.display(),
        shallowest,
        deepest,
        synth_s,
        if args.graph.cpu { "CPU" } else { "GPU" },
        a.analysis_s
    );
    println!(
        "wrote {} frames and {} to {}",
        args.frame_count,
        gif_path.display(),
        args.out_dir.display()
    );
    Ok(())
}
