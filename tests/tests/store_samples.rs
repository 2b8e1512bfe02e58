//! The sample lookup a relief reads (`StoreSample` in `store/texels.glsl`: the filtered sum,
//! the weight of the stored corners and the gradient of the alpha channel) on every store and
//! layout against its CPU reference, with an alpha that varies from voxel to voxel as a relief
//! channel does; the analytic gradient against central differences of the reference.

use glam::Vec3;
use lazysolid_compute::hash::perfect::PerfectAccess;
use lazysolid_compute::hash::{morton_decode, RobinHoodConfig};
use lazysolid_compute::store::*;
use lazysolid_compute::voxel::{VoxelGrid, Voxelizer};
use lazysolid_tests::{point_on_triangle, rng, unit_mesh, with_gpu};
use rand::Rng;
use std::collections::HashMap;

/// Sums of 8 weighted texels (and their weight gradients, of magnitude up to R) in f32: a
/// tolerance relative to R for the gradient, absolute for the rest.
const SUM_TOLERANCE: f32 = 1e-5;

/// A texel whose alpha (a relief code, 2..=255) varies smoothly along all three axes, and
/// whose colour differs between neighbouring voxels.
fn relief_texel(p: [u32; 3]) -> u32 {
    let a = 2 + (p[0] * 7 + p[1] * 3 + p[2] * 5) % 254;
    p[0] & 255 | (p[1] & 255) << 8 | ((p[2] * 7) & 255) << 16 | a << 24
}

fn close(a: StoreSample, b: StoreSample, r: u32) -> bool {
    (a.sum - b.sum).abs().max_element() <= SUM_TOLERANCE
        && (a.coverage - b.coverage).abs() <= SUM_TOLERANCE
        && (a.gradient - b.gradient).abs().max_element() <= SUM_TOLERANCE * r as f32
}

/// Points on the bunny's triangles (footprints stored) and anywhere (mostly not stored).
fn points(m: &lazysolid_renderer::mesh::Mesh, seed: u64) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut g = rng(seed);
    let mut pts = Vec::new();
    let mut nrm = Vec::new();
    for t in m.triangles.iter().step_by(7) {
        let tri = t.map(|i| m.positions[i as usize]);
        let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
        if n.length_squared() > 0.0 {
            pts.push(point_on_triangle(&mut g, tri));
            nrm.push(n.normalize());
        }
    }
    let surface = pts.len();
    pts.extend((0..300).map(|_| Vec3::new(g.random(), g.random(), g.random())));
    nrm.extend((surface..pts.len()).map(|_| Vec3::Y));
    (pts, nrm)
}

fn check<S: SparseStore>(
    store: &S,
    texel: impl Fn([u32; 3]) -> Option<u32> + Copy,
    pts: &[Vec3],
    partial_expected: bool,
) {
    let r = store.resolution();
    let got = store.sample_lookup(pts, &[]).unwrap();
    let sums = store.lookup(pts, Filter::Trilinear).unwrap();
    let mut partial = 0;
    for ((p, g), s) in pts.iter().zip(&got).zip(&sums) {
        let want = trilinear_sample_cpu(texel, *p, r);
        assert!(
            close(*g, want, r),
            "{}: at {p}: {g:?} vs {want:?}",
            store.name()
        );
        // The colour lookup is the sample's sum.
        assert!((g.sum - *s).abs().max_element() <= SUM_TOLERANCE);
        partial += (g.coverage > 0.0 && g.coverage < 1.0 - 1e-4) as usize;
    }
    assert_eq!(
        partial > 0,
        partial_expected,
        "{}: partial footprints",
        store.name()
    );
}

#[test]
fn sample_lookups_equal_their_references_on_every_store() {
    with_gpu(|gpu| {
        let kernels = StoreKernels::new(gpu).unwrap();
        let mut v = Voxelizer::new(gpu).unwrap();
        let m = unit_mesh("bunny00.off");
        let r = 64;
        let keys = v.interpolation(&m.positions, &m.triangles, r).unwrap();
        let all = keys.read().unwrap();
        let map: HashMap<[u32; 3], u32> = all
            .iter()
            .map(|&k| (morton_decode(k, 3), relief_texel(morton_decode(k, 3))))
            .collect();
        let texel = |p| map.get(&p).copied();
        let f = relief_texel;
        let source = ColourSource::Fn(&f);
        let (pts, nrm) = points(&m, 11);

        let hash =
            HashStore::build(&kernels, r, &keys, &source, RobinHoodConfig::default()).unwrap();
        check(&hash, texel, &pts, true);
        let config = OctreeConfig::for_resolution(r).unwrap();
        let (octree, _) = OctreeStore::build(&kernels, r, &keys, &source, config).unwrap();
        check(&octree, texel, &pts, true);
        let perfect =
            PerfectStore::build(&kernels, r, &keys, &source, PerfectAccess::Unconstrained).unwrap();
        check(&perfect, texel, &pts, true);
        // The blocked layout answers only inside its blocks: surface points, whole footprints.
        let cells = v
            .cells(&m.positions, &m.triangles, VoxelGrid::cells(r).unwrap())
            .unwrap();
        let blocked = PerfectStore::build_blocked(&kernels, r, &cells, &source, None).unwrap();
        let surface = pts.len() - 300;
        check(&blocked, |p| Some(f(p)), &pts[..surface], false);

        // The TileTree: GPU = CPU on the surface, coverage 1 on a tile.
        let (tree, _) = TileTree::build(
            &kernels,
            &m.positions,
            &m.triangles,
            r,
            &source,
            TileTreeConfig::default(),
        )
        .unwrap();
        let got = tree
            .sample_lookup(&pts[..surface], &nrm[..surface])
            .unwrap();
        let want = tree.sample_cpu(&pts[..surface], &nrm[..surface]).unwrap();
        let mut sloped = 0;
        for ((p, g), w) in pts.iter().zip(&got).zip(&want) {
            assert!(close(*g, *w, r), "tiletree at {p}: {g:?} vs {w:?}");
            assert_eq!(g.coverage, 1.0, "tiletree at {p}");
            sloped += (g.gradient.length() > 0.0) as usize;
        }
        assert!(
            sloped * 2 > surface,
            "{sloped} of {surface} with a gradient"
        );
    });
}

/// The analytic gradient is the derivative of the lookup: central differences of the CPU
/// reference agree inside a cell (away from its faces, where the derivative jumps).
#[test]
fn the_sample_gradient_is_the_derivative_of_the_trilinear_alpha() {
    let r = 32;
    let texel = |p: [u32; 3]| Some(relief_texel(p));
    let mut g = rng(5);
    let h = 1e-3 / r as f32;
    let mut checked = 0;
    for _ in 0..200 {
        let p = Vec3::new(g.random(), g.random(), g.random()) * 0.8 + 0.1;
        let f = (p * r as f32 - 0.5).fract();
        if f.min_element() < 0.01 || f.max_element() > 0.99 {
            continue;
        }
        let s = trilinear_sample_cpu(texel, p, r);
        assert!((s.coverage - 1.0).abs() < 1e-6);
        let fd = Vec3::from_array(std::array::from_fn(|a| {
            let mut e = Vec3::ZERO;
            e[a] = h;
            (trilinear_cpu(texel, p + e, r).w - trilinear_cpu(texel, p - e, r).w) / (2.0 * h)
        }));
        assert!(
            (s.gradient - fd).length() <= 0.02 * fd.length().max(1.0),
            "at {p}: {} vs {fd}",
            s.gradient
        );
        checked += 1;
    }
    assert!(checked > 100);
}
