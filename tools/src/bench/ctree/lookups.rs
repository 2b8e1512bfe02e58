//! Lookup throughput: a 3D tree over a mesh's whole distance volume against the four sparse
//! stores holding the same distances over the mesh's surface voxels, all read with
//! interpolation at the same points on the surface; a 2D tree against the plain R8 MIP texture
//! of the same image at the same (uv, lod).

use super::super::harness::{Bench, Throughput};
use anyhow::ensure;
use glam::{Vec3, Vec4};
use lazysolid_compute::ctree::mip_texture::{MipTexture, TimedMipLookup};
use lazysolid_compute::ctree::{CompressedTree, DeviceTree, ScalarField};
use lazysolid_compute::gpu::Gpu;
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::RobinHoodConfig;
use lazysolid_compute::store::{
    ColourSource, Filter, HashStore, OctreeConfig, OctreeStore, PerfectStore, SparseStore,
    StoreKernels, TileTree, TileTreeConfig,
};
use lazysolid_compute::voxel::Voxelizer;
use lazysolid_renderer::mesh::Mesh;
use rand::{Rng, SeedableRng};

/// Random points on the mesh's triangles (area-weighted by picking triangles uniformly is
/// enough for timing), with their triangles' normals.
fn surface_points(mesh: &Mesh, count: usize) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut g = rand_pcg::Pcg64Mcg::seed_from_u64(0xc7ee);
    let mut points = Vec::with_capacity(count);
    let mut normals = Vec::with_capacity(count);
    for _ in 0..count {
        let t = mesh.triangles[g.random_range(0..mesh.triangles.len())];
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let (mut u, mut v) = (g.random::<f32>(), g.random::<f32>());
        if u + v > 1.0 {
            (u, v) = (1.0 - u, 1.0 - v);
        }
        points.push(a + (b - a) * u + (c - a) * v);
        normals.push((b - a).cross(c - a).normalize_or_zero());
    }
    (points, normals)
}

/// The 3D tree and the four stores, trilinear, at the same surface points.
#[allow(clippy::too_many_arguments)]
pub fn volume_against_stores(
    gpu: &Gpu,
    bench: &mut Bench,
    mesh: &Mesh,
    tree: &CompressedTree,
    distance: &[f32],
    side: u32,
    count: usize,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let (points, normals) = surface_points(mesh, count);
    let case = format!("3D lookups at surface points, {side}³ distance, interpolated");
    let device = DeviceTree::upload(gpu, tree)?;
    let queries: Vec<Vec4> = points.iter().map(|p| p.extend(0.0)).collect();
    let timed = device.timed_sample(&queries)?;
    let base = "compressed tree (whole volume)";
    bench.case(
        &case,
        count as u64,
        base,
        Throughput::Items("lookup"),
        None,
        || Ok(timed.run()?),
    )?;
    let got = timed.results()?;
    for (q, v) in queries.iter().zip(&got).step_by(97) {
        ensure!(
            *v == tree.sample([q.x, q.y, q.z], 0.0),
            "tree lookup differs from its twin"
        );
    }
    notes.push(("3D tree bytes".into(), tree.size_bytes() as f64));
    let n = side as usize;
    let grey = |v: [u32; 3]| -> u32 {
        let i = v[0] as usize + n * (v[1] as usize + n * v[2] as usize);
        let g = super::images::distance_grey(distance[i.min(distance.len() - 1)], side as f32 / 4.0)
            .round() as u32;
        g | (g << 8) | (g << 16) | (255 << 24)
    };
    let source = ColourSource::Fn(&grey);
    let kernels = StoreKernels::new(gpu)?;
    let mut voxelizer = Voxelizer::new(gpu)?;
    let corners = voxelizer.interpolation(&mesh.positions, &mesh.triangles, side)?;
    let mut measure = |label: &str, store: &dyn StoreLookup| -> anyhow::Result<()> {
        let lookup = store.timed(&points, &normals)?;
        bench.case(
            &case,
            count as u64,
            label,
            Throughput::Items("lookup"),
            Some(base),
            || Ok(lookup.run()?),
        )?;
        notes.push((format!("{label} bytes"), store.bytes_of() as f64));
        Ok(())
    };
    let hash = HashStore::build(
        &kernels,
        side,
        &corners,
        &source,
        RobinHoodConfig::default(),
    )?;
    measure("coherent hash (8 lookups)", &hash)?;
    let (octree, _) = OctreeStore::build(
        &kernels,
        side,
        &corners,
        &source,
        OctreeConfig::for_resolution(side)?,
    )?;
    measure("octree (8 descents)", &octree)?;
    let access = PerfectAccess::Constrained;
    let perfect = PerfectStore::build(&kernels, side, &corners, &source, access)?;
    measure("perfect hash (8 lookups)", &perfect)?;
    let (tiles, _) = TileTree::build(
        &kernels,
        &mesh.positions,
        &mesh.triangles,
        side.next_power_of_two(),
        &source,
        TileTreeConfig::default(),
    )?;
    measure("tiletree (bilinear tile)", &tiles)?;
    Ok(())
}

/// What the comparison needs of a store, object-safe.
trait StoreLookup {
    fn timed(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
    ) -> anyhow::Result<lazysolid_compute::store::TimedLookup<'_>>;
    fn bytes_of(&self) -> u64;
}

impl<S: SparseStore> StoreLookup for S {
    fn timed(
        &self,
        points: &[Vec3],
        normals: &[Vec3],
    ) -> anyhow::Result<lazysolid_compute::store::TimedLookup<'_>> {
        Ok(self.timed_lookup(points, normals, Filter::Trilinear)?)
    }
    fn bytes_of(&self) -> u64 {
        self.bytes()
    }
}

/// The 2D tree against the plain MIP texture of the same image.
pub fn image_against_mip(
    gpu: &Gpu,
    bench: &mut Bench,
    field: &ScalarField,
    tree: &CompressedTree,
    count: usize,
    notes: &mut Vec<(String, f64)>,
) -> anyhow::Result<()> {
    let mut g = rand_pcg::Pcg64Mcg::seed_from_u64(0x2d);
    let queries: Vec<Vec4> = (0..count)
        .map(|_| {
            Vec4::new(
                g.random::<f32>(),
                g.random::<f32>(),
                0.0,
                g.random_range(0.0..2.0),
            )
        })
        .collect();
    let [w, h, _] = field.size;
    let grey: Vec<u8> = field
        .values
        .iter()
        .map(|v| v.round().clamp(0.0, 255.0) as u8)
        .collect();
    let texture = MipTexture::new(w, h, &grey);
    let case = format!("2D lookups, {w}×{h} terrain, interpolated, lod 0–2");
    let mip = TimedMipLookup::new(gpu, &texture, &queries)?;
    let base = "plain R8 MIP texture (trilinear)";
    bench.case(
        &case,
        count as u64,
        base,
        Throughput::Items("lookup"),
        None,
        || Ok(mip.run()?),
    )?;
    let got = mip.results()?;
    for (q, v) in queries.iter().zip(&got).step_by(101) {
        let cpu = texture.sample([q.x, q.y], q.w);
        ensure!(
            (v - cpu).abs() <= 1e-3,
            "MIP lookup {v} differs from its twin {cpu}"
        );
    }
    let device = DeviceTree::upload(gpu, tree)?;
    let timed = device.timed_sample(&queries)?;
    bench.case(
        &case,
        count as u64,
        "compressed tree (primal, fractional lod)",
        Throughput::Items("lookup"),
        Some(base),
        || Ok(timed.run()?),
    )?;
    notes.push(("2D tree bytes".into(), tree.size_bytes() as f64));
    notes.push(("2D MIP texture bytes".into(), texture.bytes() as f64));
    Ok(())
}
