//! The datasets of `bench hash`: points of a 2D or 3D grid, each with a payload, plus as many
//! absent points for negative queries. Points are kept in raster order (x fastest), the order a
//! screen or a slice traversal visits them; keys come from the layout under test.

use anyhow::Context;
use glam::Vec3;
use lazysolid_compute::hash::{KeyLayout, Universe};
use lazysolid_renderer::mesh::Mesh;
use rand::{Rng, SeedableRng};
use std::collections::HashSet;
use std::path::Path;

/// One dataset.
pub struct Dataset {
    /// Short name for tables and files.
    pub name: String,
    /// What it is, for the report.
    pub description: String,
    /// Grid extents.
    pub dims: [u32; 3],
    /// 2 or 3.
    pub dimensions: u32,
    /// Defined points, raster order.
    pub points: Vec<[u32; 3]>,
    /// Payloads (for images: 0xRRGGBB).
    pub payloads: Vec<u32>,
    /// As many undefined points, raster order.
    pub absent: Vec<[u32; 3]>,
}

impl Dataset {
    /// The universe under `layout`.
    pub fn universe(&self, layout: KeyLayout) -> Universe {
        if self.dimensions == 2 {
            Universe::new_2d(self.dims[0], self.dims[1], layout).expect("valid extents")
        } else {
            Universe::new_3d(self.dims, layout).expect("valid extents")
        }
    }
}

fn raster_key(p: &[u32; 3], dims: [u32; 3]) -> u64 {
    p[0] as u64 + dims[0] as u64 * (p[1] as u64 + dims[1] as u64 * p[2] as u64)
}

/// `count` points not in `defined`, drawn uniformly, in raster order.
fn absent_points(dims: [u32; 3], defined: &HashSet<u64>, count: usize, seed: u64) -> Vec<[u32; 3]> {
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut chosen = HashSet::new();
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let p = [
            rng.random_range(0..dims[0]),
            rng.random_range(0..dims[1]),
            rng.random_range(0..dims[2]),
        ];
        let k = raster_key(&p, dims);
        if !defined.contains(&k) && chosen.insert(k) {
            out.push(p);
        }
    }
    out.sort_by_key(|p| raster_key(p, dims));
    out
}

/// The mesh at `path`, scaled into the unit cube.
fn load_normalized(path: &Path) -> anyhow::Result<Mesh> {
    Mesh::load_unit_cube(path)
        .with_context(|| format!("loading {} (run scripts/fetch-assets.sh)", path.display()))
}

/// `count` distinct uniformly random points of a `size`² universe (the paper: 1M keys in 8K²).
pub fn random_2d(size: u32, count: usize, seed: u64) -> Dataset {
    let dims = [size, size, 1];
    let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
    let mut set = HashSet::with_capacity(count);
    let mut points = Vec::with_capacity(count);
    while points.len() < count {
        let p = [rng.random_range(0..size), rng.random_range(0..size), 0];
        if set.insert(raster_key(&p, dims)) {
            points.push(p);
        }
    }
    points.sort_by_key(|p| raster_key(p, dims));
    let payloads = (0..count as u32).collect();
    let absent = absent_points(dims, &set, count, seed + 1);
    Dataset {
        name: "random-2d".into(),
        description: format!("{count} uniformly random points of {size}x{size}"),
        dims,
        dimensions: 2,
        points,
        payloads,
        absent,
    }
}

/// The defined pixels of a large sparse image: the armadillo mesh seen from the front,
/// rasterized at `size`², each pixel holding its shaded colour (like the paper's flower and
/// datafish images: coherent regions of defined pixels).
pub fn armadillo_image(mesh_path: &Path, size: u32) -> anyhow::Result<Dataset> {
    let mesh = load_normalized(mesh_path)?;
    let s = size as f32;
    let mut depth = vec![f32::NEG_INFINITY; (size * size) as usize];
    let mut colour = vec![0u32; (size * size) as usize];
    let light = Vec3::new(0.4, 0.5, 0.77).normalize();
    for t in &mesh.triangles {
        let v = [
            mesh.positions[t[0] as usize],
            mesh.positions[t[1] as usize],
            mesh.positions[t[2] as usize],
        ];
        let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
        let shade = 0.15 + 0.85 * n.dot(light).abs();
        let rgb =
            ((shade * 235.0) as u32) << 16 | ((shade * 205.0) as u32) << 8 | (shade * 160.0) as u32;
        // Pixel (x, y): x right, y down, so the image is upright.
        let p: Vec<(f32, f32, f32)> = v.iter().map(|q| (q.x * s, (1.0 - q.y) * s, q.z)).collect();
        let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
        if area.abs() < 1e-12 {
            continue;
        }
        let x0 = p
            .iter()
            .map(|q| q.0)
            .fold(f32::MAX, f32::min)
            .floor()
            .max(0.0) as u32;
        let x1 = (p.iter().map(|q| q.0).fold(f32::MIN, f32::max).ceil() as u32).min(size - 1);
        let y0 = p
            .iter()
            .map(|q| q.1)
            .fold(f32::MAX, f32::min)
            .floor()
            .max(0.0) as u32;
        let y1 = (p.iter().map(|q| q.1).fold(f32::MIN, f32::max).ceil() as u32).min(size - 1);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                let w0 = ((p[1].0 - px) * (p[2].1 - py) - (p[2].0 - px) * (p[1].1 - py)) / area;
                let w1 = ((p[2].0 - px) * (p[0].1 - py) - (p[0].0 - px) * (p[2].1 - py)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * p[0].2 + w1 * p[1].2 + w2 * p[2].2;
                let i = (y * size + x) as usize;
                if z > depth[i] {
                    depth[i] = z;
                    colour[i] = rgb;
                }
            }
        }
    }
    let dims = [size, size, 1];
    let mut points = Vec::new();
    let mut payloads = Vec::new();
    let mut set = HashSet::new();
    for y in 0..size {
        for x in 0..size {
            let i = (y * size + x) as usize;
            if depth[i] > f32::NEG_INFINITY {
                points.push([x, y, 0]);
                payloads.push(colour[i]);
                set.insert(raster_key(&[x, y, 0], dims));
            }
        }
    }
    let absent = absent_points(dims, &set, points.len(), 7);
    let n = points.len();
    Ok(Dataset {
        name: "image".into(),
        description: format!(
            "armadillo front view rasterized at {size}x{size}: {n} defined pixels ({:.1}%)",
            100.0 * n as f64 / (size as f64 * size as f64)
        ),
        dims,
        dimensions: 2,
        points,
        payloads,
        absent,
    })
}

/// The voxelized surface of the armadillo at `resolution`³ (exact triangle–box overlap).
pub fn armadillo_voxels(mesh_path: &Path, resolution: u32) -> anyhow::Result<Dataset> {
    let mesh = load_normalized(mesh_path)?;
    let keys =
        lazysolid_compute::voxel::surface_voxels_cpu(&mesh.positions, &mesh.triangles, resolution);
    let dims = [resolution; 3];
    let mut points: Vec<[u32; 3]> = keys
        .iter()
        .map(|&k| lazysolid_compute::hash::morton_decode(k, 3))
        .collect();
    points.sort_by_key(|p| raster_key(p, dims));
    let set: HashSet<u64> = points.iter().map(|p| raster_key(p, dims)).collect();
    // Payload: the voxel's position as colour, like colour voxel data.
    let payloads = points
        .iter()
        .map(|p| {
            (p[0] >> (resolution.trailing_zeros().saturating_sub(8))) << 16
                | (p[1] >> (resolution.trailing_zeros().saturating_sub(8))) << 8
                | (p[2] >> (resolution.trailing_zeros().saturating_sub(8)))
        })
        .collect();
    let absent = absent_points(dims, &set, points.len(), 11);
    let n = points.len();
    Ok(Dataset {
        name: "voxels".into(),
        description: format!("armadillo surface voxelized at {resolution}^3: {n} voxels"),
        dims,
        dimensions: 3,
        points,
        payloads,
        absent,
    })
}
