//! `lazysolid bench trace`: ray throughput of the GLSL CWBVH traversal on the device next to
//! obvhs's CPU traversal of the same BVH and rays on 2 threads, plus BVH build times.
//!
//! Two ray sets, both computed once on the CPU so that every implementation traces the very
//! same rays: primary rays of a pinhole camera framing the mesh, and diffuse-bounce rays
//! (cosine-distributed about the geometric normal at each primary hit): incoherent rays, the
//! hard case of any traversal.

use super::harness::{time_cpu, time_gpu, Bench, Throughput};
use super::plot::bar_chart;
use super::CommonArgs;
use crate::cli::resolution::Resolution;
use crate::cli::{assets, GlobalArgs};
use anyhow::{ensure, Context};
use clap::Args;
use glam::{Affine3A, Vec3};
use lazysolid_compute::gpu::GpuBuffer;
use lazysolid_renderer::accel::{
    DeviceBvh, GpuRay, GpuRayHit, InstanceDesc, MeshBvh, QueryKind, RayQueries, SceneBvh, NO_HIT,
};
use lazysolid_renderer::mesh::Mesh;
use obvhs::ray::{Ray, RayHit};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;

/// What to trace.
#[derive(Args)]
pub struct TraceArgs {
    #[command(flatten)]
    pub common: CommonArgs,
    /// The mesh: a name in the assets' meshes (armadillo, bunny00, ...) or a path to an OFF or
    /// OBJ file; normalized into the unit cube.
    #[arg(long, value_name = "NAME|PATH", default_value = "armadillo")]
    pub mesh: String,
    /// Primary rays: one per pixel of an image of WxH pixels (N for NxN).
    #[arg(long, value_name = "WxH", default_value = "1024x1024")]
    pub res: Resolution,
    /// CPU threads of the obvhs baseline.
    #[arg(long, default_value_t = 2)]
    pub cpu_threads: usize,
}

/// Runs the suite.
pub fn run(args: &TraceArgs, global: &GlobalArgs) -> anyhow::Result<()> {
    crate::bench::plot::ensure_font()?;
    args.res.check("--res", 16..=4096)?;
    ensure!(args.cpu_threads >= 1, "--cpu-threads must be at least 1");
    let mesh_path = assets::mesh("--mesh", &args.mesh)?;
    let mesh = Mesh::load_unit_cube(&mesh_path)
        .with_context(|| format!("loading --mesh {}", mesh_path.display()))?;
    let gpu = global.gpu()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.cpu_threads)
        .build()?;
    let mut bench = Bench::new("bench-trace", &gpu, &args.common, 8)?;
    let tris = mesh.triangles.len() as u64;
    let threads = args.cpu_threads;

    // Builds.
    let mut mesh_bvh = None;
    bench.case(
        "bvh build (mesh, medium)",
        tris,
        "cpu obvhs cwbvh (rayon)",
        Throughput::Elements,
        None,
        || {
            let (b, ms) = time_cpu(|| pool.install(|| MeshBvh::build(&mesh)));
            mesh_bvh = Some(b);
            Ok(ms)
        },
    )?;
    let mesh_bvh = mesh_bvh.expect("built at least once");
    let instance = InstanceDesc {
        mesh: 0,
        material: 0,
        transform: Affine3A::IDENTITY,
    };
    let scene = SceneBvh::build(&[&mesh], &[instance]);
    let device = DeviceBvh::upload(&gpu, &scene)?;
    let queries = RayQueries::new(&gpu)?;

    // Ray sets.
    let primary = primary_rays(args.res);
    let first_hits: Vec<GpuRayHit> =
        pool.install(|| primary.par_iter().map(|r| scene.trace_cpu(r)).collect());
    let bounce = bounce_rays(&primary, &first_hits, &mesh);
    ensure!(!bounce.is_empty(), "no primary ray hits the mesh");

    let mut rates = Vec::new();
    for (case, rays) in [("primary rays", &primary), ("diffuse bounce rays", &bounce)] {
        let n = rays.len() as u64;
        let cpu_single = format!("cpu obvhs cwbvh ({threads} threads)");
        let cpu_two = format!("cpu obvhs cwbvh two-level ({threads} threads)");
        let gpu_name = "gpu cwbvh two-level";
        let ray_buf = GpuBuffer::from_slice(&gpu, "bench rays", rays)?;
        let hit_buf = GpuBuffer::<GpuRayHit>::zeroed(&gpu, "bench hits", rays.len())?;
        let gpu_ms = bench.case(
            case,
            n,
            gpu_name,
            Throughput::Elements,
            Some(&cpu_single),
            || {
                time_gpu(&gpu, |rec| {
                    queries.record(rec, &device, &ray_buf, &hit_buf, QueryKind::Closest)
                })
            },
        )?;
        let gpu_hits = hit_buf.read()?;
        let mut cpu_hits = Vec::new();
        let cpu_ms = bench.case(case, n, &cpu_single, Throughput::Elements, None, || {
            let (h, ms) = time_cpu(|| pool.install(|| trace_single_level(&mesh_bvh, rays)));
            cpu_hits = h;
            Ok(ms)
        })?;
        bench.case(
            case,
            n,
            &cpu_two,
            Throughput::Elements,
            Some(&cpu_single),
            || {
                Ok(time_cpu(|| {
                    pool.install(|| {
                        rays.par_iter()
                            .map(|r| scene.trace_cpu(r))
                            .collect::<Vec<_>>()
                    })
                })
                .1)
            },
        )?;
        let mismatched = gpu_hits
            .iter()
            .zip(&cpu_hits)
            .filter(|(g, c)| g.triangle != c.0 || (g.instance == NO_HIT) != (c.0 == NO_HIT))
            .count();
        ensure!(
            mismatched * 10_000 <= rays.len(),
            "{case}: the GPU and obvhs disagree on {mismatched} of {} rays",
            rays.len()
        );
        rates.push((
            case.to_string(),
            n as f64 / (gpu_ms * 1e-3) / 1e6,
            n as f64 / (cpu_ms * 1e-3) / 1e6,
        ));
    }
    let dir = bench.artifact_dir()?;
    bar_chart(
        &dir.join("trace-rates.png"),
        &format!(
            "{} ({} triangles): rays per second",
            mesh_path.file_name().unwrap_or_default().to_string_lossy(),
            tris
        ),
        "ray set",
        "Mrays/s",
        &rates.iter().map(|r| r.0.clone()).collect::<Vec<_>>(),
        &[
            (
                format!("{} (GLSL CWBVH)", gpu.info().name),
                rates.iter().map(|r| r.1).collect(),
            ),
            (
                format!("obvhs CPU, {threads} threads"),
                rates.iter().map(|r| r.2).collect(),
            ),
        ],
        false,
    )?;
    let notes = vec![
        ("triangles".to_string(), tris as f64),
        ("bvh nodes".to_string(), mesh_bvh.bvh.nodes.len() as f64),
        ("bvh gpu bytes".to_string(), device.bytes() as f64),
        ("primary rays".to_string(), primary.len() as f64),
        (
            "primary hit fraction".to_string(),
            first_hits.iter().filter(|h| h.instance != NO_HIT).count() as f64
                / primary.len() as f64,
        ),
        ("bounce rays".to_string(), bounce.len() as f64),
    ];
    bench.finish(&notes)?;
    Ok(())
}

/// obvhs's own single-level traversal: what a CPU user of obvhs would run.
fn trace_single_level(b: &MeshBvh, rays: &[GpuRay]) -> Vec<(u32, f32)> {
    rays.par_iter()
        .map(|r| {
            let ray = Ray::new(r.origin.into(), r.direction.into(), r.tmin, r.tmax);
            let mut hit = RayHit::none();
            if b.bvh.ray_traverse(ray, &mut hit, |ray, id| {
                b.triangles[b.bvh.primitive_indices[id] as usize].intersect(ray)
            }) {
                (b.bvh.primitive_indices[hit.primitive_id as usize], hit.t)
            } else {
                (NO_HIT, f32::INFINITY)
            }
        })
        .collect()
}

/// A pinhole camera at (0.5, 0.55, 2.2) looking at the unit cube's centre, 35° vertical field
/// of view; rays in 8×8-pixel tiles, the order in which a renderer launches them.
fn primary_rays(res: Resolution) -> Vec<GpuRay> {
    let (w, h) = (res.width, res.height);
    let eye = Vec3::new(0.5, 0.55, 2.2);
    let forward = (Vec3::new(0.5, 0.5, 0.5) - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let half = (35f32.to_radians() * 0.5).tan();
    let aspect = w as f32 / h as f32;
    let tiles_x = w.div_ceil(8);
    let pixel = |i: u32| {
        let (tile, within) = (i / 64, i % 64);
        (
            (tile % tiles_x) * 8 + within % 8,
            (tile / tiles_x) * 8 + within / 8,
        )
    };
    (0..tiles_x * h.div_ceil(8) * 64)
        .map(pixel)
        .filter(|&(x, y)| x < w && y < h)
        .map(|(x, y)| {
            let sx = ((x as f32 + 0.5) / w as f32 * 2.0 - 1.0) * half * aspect;
            let sy = (1.0 - (y as f32 + 0.5) / h as f32 * 2.0) * half;
            GpuRay {
                origin: eye.into(),
                tmin: 0.0,
                direction: (forward + right * sx + up * sy).normalize().into(),
                tmax: f32::INFINITY,
            }
        })
        .collect()
}

/// One cosine-distributed bounce from every primary hit, leaving from the side the primary
/// ray came from (deterministic seed).
fn bounce_rays(primary: &[GpuRay], hits: &[GpuRayHit], mesh: &Mesh) -> Vec<GpuRay> {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(17);
    primary
        .iter()
        .zip(hits)
        .filter(|(_, h)| h.instance != NO_HIT)
        .map(|(r, h)| {
            let [a, b, c] = mesh.triangles[h.triangle as usize].map(|i| mesh.positions[i as usize]);
            let mut n = (b - a).cross(c - a).normalize();
            let d = Vec3::from(r.direction);
            if n.dot(d) > 0.0 {
                n = -n;
            }
            let p = Vec3::from(r.origin) + d * h.t + n * 1e-4;
            let (u1, u2): (f32, f32) = (rng.random(), rng.random());
            let (s, phi) = (u1.sqrt(), std::f32::consts::TAU * u2);
            let t = n.any_orthonormal_vector();
            let bt = n.cross(t);
            let dir = t * (s * phi.cos()) + bt * (s * phi.sin()) + n * (1.0 - u1).max(0.0).sqrt();
            GpuRay {
                origin: p.into(),
                tmin: 0.0,
                direction: dir.normalize().into(),
                tmax: f32::INFINITY,
            }
        })
        .collect()
}
