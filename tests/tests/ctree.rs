//! Compressed random-access trees: the GLSL lookup against its CPU twin, bit for bit, on 2D and
//! 3D trees at lattice points, random points and fractional levels of detail.

use crate::uv_maps::quad_scene_sized;
use glam::{UVec4, Vec4};
use lazysolid_compute::ctree::fields::{terrain, torus_distance};
use lazysolid_compute::ctree::lookup::{LOD_FRAC_BITS, POS_FRAC_BITS};
use lazysolid_compute::ctree::{
    Border, CompressedTree, CtreeBuilder, CtreeOptions, DeviceTree, DownloadedTree, ScalarField,
};
use lazysolid_renderer::diff::flip_images;
use lazysolid_renderer::output::{tonemapped_rgb8, Operator, ToneMap};
use lazysolid_tests::{render_scene_text, rng, with_gpu};
use rand::Rng;

fn queries(tree: &CompressedTree, count: usize, seed: u64) -> Vec<UVec4> {
    let mut g = rng(seed);
    let d = tree.lattice.dims as usize;
    let limit = tree.lattice.extent() << POS_FRAC_BITS;
    let finest = tree.lattice.finest() << LOD_FRAC_BITS;
    (0..count)
        .map(|i| {
            let mut q = [0u32; 4];
            for (k, v) in q.iter_mut().enumerate().take(d) {
                *v = if i % 3 == 0 {
                    // A sample of the field.
                    g.random_range(0..tree.size[k]) << POS_FRAC_BITS
                } else {
                    g.random_range(0..=limit + 300)
                };
            }
            q[3] = match i % 4 {
                0 => 0,
                1 => g.random_range(0..finest + 600),
                2 => g.random_range(0..4) << LOD_FRAC_BITS,
                _ => g.random_range(0..3 << LOD_FRAC_BITS),
            };
            UVec4::from_array(q)
        })
        .collect()
}

fn check_lookups(tree: &CompressedTree, seed: u64) {
    with_gpu(|gpu| {
        let device = DeviceTree::upload(gpu, tree).unwrap();
        let qs = queries(tree, 6000, seed);
        let gpu_values = device.lookup_fixed(&qs).unwrap();
        for (q, &v) in qs.iter().zip(&gpu_values) {
            let cpu = tree.lookup_fixed([q.x, q.y, q.z], q.w);
            assert_eq!(v, cpu, "fixed lookup at {q:?}");
        }
        let mut g = rng(seed + 1);
        let samples: Vec<Vec4> = (0..3000)
            .map(|_| {
                Vec4::new(
                    g.random_range(-0.1..1.1),
                    g.random_range(-0.1..1.1),
                    g.random_range(-0.1..1.1),
                    g.random_range(0.0..4.0),
                )
            })
            .collect();
        let gpu_samples = device.sample(&samples).unwrap();
        for (s, &v) in samples.iter().zip(&gpu_samples) {
            let cpu = tree.sample([s.x, s.y, s.z], s.w);
            assert_eq!(v.to_bits(), cpu.to_bits(), "sample at {s:?}");
        }
    });
}

#[test]
fn glsl_lookups_equal_the_cpu_twin_in_2d_and_3d() {
    let opts = |step, forest| CtreeOptions {
        step,
        forest,
        ..Default::default()
    };
    let field = terrain(129, 97, 5);
    check_lookups(&CompressedTree::build(&field, &opts(1.0, None)).unwrap(), 1);
    check_lookups(
        &CompressedTree::build(&field, &opts(6.0, Some(2))).unwrap(),
        2,
    );
    let volume = torus_distance(21);
    check_lookups(
        &CompressedTree::build(&volume, &opts(2.0, None)).unwrap(),
        3,
    );
    // A constant field is all forest: no subtree at all.
    let flat = ScalarField::new("flat", 2, [40, 40, 1], vec![77.0; 1600]).unwrap();
    let tree = CompressedTree::build(&flat, &opts(1.0, None)).unwrap();
    assert!(tree.bytes.is_empty());
    check_lookups(&tree, 4);
}

fn noise(side: u32, seed: u64) -> ScalarField {
    let mut g = rng(seed);
    let values = (0..side * side)
        .map(|_| g.random_range(0.0..255.0))
        .collect();
    ScalarField::new("noise", 2, [side, side, 1], values).unwrap()
}

#[test]
fn the_device_build_equals_the_cpu_build_byte_for_byte() {
    with_gpu(|gpu| {
        let mut builder = CtreeBuilder::new(gpu).unwrap();
        let opts = |step, forest| CtreeOptions {
            step,
            forest,
            ..Default::default()
        };
        let cases = [
            (terrain(200, 150, 9), opts(1.0, None)),
            (terrain(200, 150, 9), opts(0.25, Some(1))),
            (terrain(65, 65, 2), opts(8.0, None)),
            (noise(48, 3), opts(2.0, None)),
            (torus_distance(19), opts(1.5, None)),
            (
                terrain(200, 150, 9),
                CtreeOptions {
                    border: Border::Free,
                    ..opts(1.0, None)
                },
            ),
            (
                torus_distance(19),
                CtreeOptions {
                    border: Border::Free,
                    ..opts(1.5, None)
                },
            ),
            (
                ScalarField::new("flat", 3, [9, 9, 9], vec![3.0; 729]).unwrap(),
                opts(1.0, None),
            ),
        ];
        for (field, options) in &cases {
            let cpu = CompressedTree::build(field, options).unwrap();
            let (device, report) = builder.build(field, options).unwrap();
            let got = device.download().unwrap();
            let want = DownloadedTree::of(&cpu);
            assert_eq!(got.forest, want.forest, "{:?} {options:?}", field.size);
            assert_eq!(got.levels, want.levels, "{:?} {options:?}", field.size);
            assert_eq!(
                got.indirection, want.indirection,
                "{:?} {options:?}",
                field.size
            );
            assert_eq!(got.mipmap, want.mipmap, "{:?} {options:?}", field.size);
            assert!(
                got.bytes == want.bytes,
                "{:?} {options:?}: records differ",
                field.size
            );
            assert_eq!(device.size_bytes(), cpu.size_bytes());
            let padding: Vec<u64> = cpu.stats.rows[..report.padding.len()]
                .iter()
                .map(|r| r.padding)
                .collect();
            assert_eq!(report.padding, padding);
            // The device-built tree answers lookups as the host's does.
            let qs = queries(&cpu, 500, 7);
            let values = device.lookup_fixed(&qs).unwrap();
            for (q, v) in qs.iter().zip(values) {
                assert_eq!(v, cpu.lookup_fixed([q.x, q.y, q.z], q.w));
            }
        }
    });
}

/// A quad seen from above whose albedo map is read through its compressed trees renders like the
/// same map read through its MIP pyramid: the same samples, so the only difference is the
/// trees' quantization and their interpolation in sRGB YCoCg instead of linear RGB.
#[test]
fn a_scene_renders_an_albedo_map_read_through_compressed_trees() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (96u32, 64u32);
    let terrain = terrain(w, h, 4);
    let img = image::RgbImage::from_fn(w, h, |x, y| {
        let v = terrain.values[(y * w + x) as usize];
        let t = x as f32 / w as f32;
        image::Rgb([v as u8, (0.6 * v + 90.0 * t) as u8, (200.0 - 0.5 * v) as u8])
    });
    img.save(dir.path().join("smooth.png")).unwrap();
    let scene = |extra: &str| {
        let material = format!("kind = \"lambertian\"\nalbedo_map = \"smooth.png\"\n{extra}");
        quad_scene_sized(&material, 64, 4)
    };
    let tone = ToneMap {
        exposure_ev: 0.0,
        operator: Operator::Clamp,
    };
    let picture = |extra: &str| {
        tonemapped_rgb8(&render_scene_text(dir.path(), &scene(extra)), &tone).unwrap()
    };
    let plain = picture("");
    let near = flip_images(&plain, &picture("albedo_ctree_step = 1.0")).unwrap();
    let far = flip_images(&plain, &picture("albedo_ctree_step = 24.0")).unwrap();
    println!(
        "FLIP mean against the MIP pyramid: step 1 {}, step 24 {}",
        near.mean, far.mean
    );
    // Stated limit: FLIP mean 0.02 at step 1 (the map's texels within half a grey level).
    assert!(near.mean < 0.02, "step 1: FLIP mean {}", near.mean);
    // The check can fail: a coarse step visibly changes the picture.
    assert!(
        far.mean > near.mean * 2.0,
        "step 24: {} against {}",
        far.mean,
        near.mean
    );
    // A step on a material without an albedo map is refused, naming the key.
    let path = dir.path().join("bad.toml");
    let bad = scene("albedo_ctree_step = 1.0")
        .replace("albedo_map = \"smooth.png\"\n", "color = [0.5, 0.5, 0.5]\n");
    std::fs::write(&path, bad).unwrap();
    let err = lazysolid_renderer::scene::Scene::load(&path)
        .unwrap_err()
        .to_string();
    assert!(err.contains("albedo_ctree_step"), "{err}");
}
