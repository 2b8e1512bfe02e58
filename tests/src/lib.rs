//! Shared helpers for lazysolid's integration tests.
//!
//! Every test runs on the device the environment picks (lavapipe on CI) with the Khronos
//! validation layer required. [`with_gpu`] fails the test on any validation error and on any
//! GPU object that outlives the test; [`with_fresh_gpu`] also destroys the device, so the
//! layer's report of leaked Vulkan objects counts too.

pub mod shader_constants;

/// The test-only kernels, compiled from `glsl/render_test/` by this crate's `build.rs`.
pub mod kernels {
    include!(concat!(env!("OUT_DIR"), "/kernels.rs"));
}

use lazysolid_compute::gpu::{DeviceAddress, Gpu, GpuOptions, PushRegistration};
use lazysolid_compute::hash::Universe;
use lazysolid_renderer::glint::synthetic::{self, BumpExtent};
use rand::{Rng, SeedableRng};
use std::sync::Mutex;

/// Devices of [`GpuOptions::for_tests`] that finished a test cleanly, for the next tests.
static DEVICES: Mutex<Vec<Gpu>> = Mutex::new(Vec::new());

/// Runs `test` on a validated device of the test options, kept from an earlier test when one
/// is free, and asserts that the validation layer reported no error during the test and that
/// no GPU object outlived it (the device is again owned by its handle and kernel cache
/// alone). A kept device keeps its kernel cache: lavapipe translates a kernel's SPIR-V
/// again for every device, which is most of what creating a path tracer costs (60 % of the
/// 3.25 s it took for the textured test scene, docs/testing.md), so a device per test spent
/// minutes of the suite building the same pipelines. Tests that count pipelines, meters or
/// destruction from a device's creation use [`with_fresh_gpu`].
pub fn with_gpu<R>(test: impl FnOnce(&Gpu) -> R) -> R {
    let kept = DEVICES.lock().unwrap_or_else(|p| p.into_inner()).pop();
    let gpu = kept.unwrap_or_else(|| {
        Gpu::new(&GpuOptions::for_tests())
            .unwrap_or_else(|e| panic!("cannot create the test device: {e}"))
    });
    assert!(gpu.validation_enabled());
    let log = gpu.validation_log();
    let (errors, reported) = (log.errors(), log.messages().len());
    let result = test(&gpu);
    assert!(
        gpu.is_sole_owner(),
        "a GPU object outlived its test (a buffer, kernel or device handle is still alive)"
    );
    assert_eq!(
        log.errors(),
        errors,
        "validation errors: {:#?}",
        &log.messages()[reported..]
    );
    DEVICES.lock().unwrap_or_else(|p| p.into_inner()).push(gpu);
    result
}

/// Runs `test` on a new validated device, then destroys the device and asserts that the
/// validation layer reported no error, leaks included (the layer reports those only when the
/// device is destroyed), and that no GPU object outlived the test.
pub fn with_fresh_gpu<R>(test: impl FnOnce(&Gpu) -> R) -> R {
    with_gpu_options(&GpuOptions::for_tests(), test)
}

/// [`with_gpu`] on a device created with `options` (validation must be required in them), for
/// tests that pin a setting the environment would otherwise choose, e.g. the memory mode.
pub fn with_gpu_options<R>(options: &GpuOptions, test: impl FnOnce(&Gpu) -> R) -> R {
    let gpu = Gpu::new(options).unwrap_or_else(|e| panic!("cannot create the test device: {e}"));
    assert!(gpu.validation_enabled());
    let log = gpu.validation_log();
    let weak = gpu.downgrade();
    let result = test(&gpu);
    drop(gpu);
    assert!(
        weak.is_destroyed(),
        "a GPU object outlived its test, so the device was not destroyed"
    );
    assert_eq!(log.errors(), 0, "validation errors: {:#?}", log.messages());
    result
}

/// A deterministic random generator for test data.
pub fn rng(seed: u64) -> rand_pcg::Pcg64Mcg {
    rand_pcg::Pcg64Mcg::seed_from_u64(seed)
}

/// The glint tests' example: the generated bumps-and-scratches field, every bump evaluated at
/// every texel.
pub fn bumps_and_scratches(size: usize, seed: u64) -> Vec<f32> {
    synthetic::bumps_and_scratches(size, seed, BumpExtent::Everywhere)
}

/// `n` distinct random points of `u` as keys, and the keys of `absent` other points (keys
/// that a table built from the first `n` must reject).
pub fn random_keys(u: &Universe, n: usize, absent: usize, seed: u64) -> (Vec<u64>, Vec<u64>) {
    let mut r = rng(seed);
    let mut seen = std::collections::HashSet::new();
    let mut keys = Vec::new();
    while keys.len() < n + absent {
        let p = [
            r.random_range(0..u.dims[0]),
            r.random_range(0..u.dims[1]),
            r.random_range(0..u.dims[2]),
        ];
        if seen.insert(p) {
            keys.push(u.key(p));
        }
    }
    let missing = keys.split_off(n);
    (keys, missing)
}

/// `n` random `u32` drawn with `seed`.
pub fn random_u32(n: usize, seed: u64) -> Vec<u32> {
    let mut r = rng(seed);
    (0..n).map(|_| r.random()).collect()
}

/// Sizes every primitive must handle: empty, one, around workgroup and tile boundaries,
/// non-powers of two and several tiles.
pub const EDGE_SIZES: &[usize] = &[
    0, 1, 2, 3, 4, 5, 7, 255, 256, 257, 1000, 4095, 4096, 4097, 65_537, 1_000_003,
];

/// Path of `assets/<folder>/<name>`, installed by `scripts/fetch-assets.sh`; panics with the
/// fix when it is absent.
fn asset(folder: &str, name: &str) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../assets")
        .join(folder)
        .join(name);
    assert!(
        path.exists(),
        "{} is missing: run scripts/fetch-assets.sh (the README's test command does)",
        path.display()
    );
    path
}

/// Writes `text` as `dir/scene.toml`, loads it (relative paths from `dir`) and renders it on
/// the test device: for tests whose scene is written next to the files it names.
pub fn render_scene_text(dir: &std::path::Path, text: &str) -> lazysolid_renderer::output::Film {
    use lazysolid_renderer::{render::PathTracer, scene::Scene};
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    with_gpu(|gpu| {
        let mut t = PathTracer::new(gpu, &scene).unwrap();
        t.render(|_| {}).unwrap()
    })
}

/// Path of a mesh installed by `scripts/fetch-assets.sh`; panics with the fix when it is absent.
pub fn asset_mesh(name: &str) -> std::path::PathBuf {
    asset("meshes", name)
}

/// Path of a GIMP pattern installed by `scripts/fetch-assets.sh` into `assets/exemplars/`;
/// panics with the fix when it is absent.
pub fn asset_exemplar(name: &str) -> std::path::PathBuf {
    asset("exemplars", name)
}

/// A `width`×`height` crop at (`x0`, `y0`) of a GIMP pattern of the assets (`file`, e.g.
/// `terra.pat`), named after it: small exemplars keep analyses and syntheses quick.
pub fn exemplar_crop(
    file: &str,
    x0: u32,
    y0: u32,
    width: u32,
    height: u32,
) -> lazysolid_synth::Exemplar {
    use lazysolid_synth::Exemplar;
    let full = Exemplar::load(&asset_exemplar(file)).unwrap_or_else(|e| panic!("{e}"));
    let rgb = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| full.at(x0 + x, y0 + y))
        .collect();
    let name = format!("{} crop", file.trim_end_matches(".pat"));
    Exemplar::from_rgb(name, width, height, rgb).unwrap_or_else(|e| panic!("{e}"))
}

/// An asset mesh moved into the unit cube, the space of voxel grids, stores and test scenes.
pub fn unit_mesh(name: &str) -> lazysolid_renderer::mesh::Mesh {
    lazysolid_renderer::mesh::Mesh::load_unit_cube(asset_mesh(name))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// A uniformly distributed point of the triangle `[p0, p1, p2]` (two draws of `g`, folded
/// back into the triangle when they fall in the other half of the parallelogram).
pub fn point_on_triangle(g: &mut impl Rng, [p0, p1, p2]: [glam::Vec3; 3]) -> glam::Vec3 {
    let (a, b): (f32, f32) = (g.random(), g.random());
    let (a, b) = if a + b > 1.0 {
        (1.0 - a, 1.0 - b)
    } else {
        (a, b)
    };
    p0 + (p1 - p0) * a + (p2 - p0) * b
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render_test/shading_test.comp`, the kernel that runs the GLSL shading
    /// library on test cases.
    #[derive(Clone, Copy)]
    pub struct ShadingTestPush<'a> {
        /// The cases.
        pub cases: DeviceAddress<'a>,
        /// One result row per case.
        pub results: DeviceAddress<'a>,
        /// The `Environment` record.
        pub environment: DeviceAddress<'a>,
        /// Which function the cases exercise.
        pub mode: u32,
        /// Number of cases.
        pub n: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render_test/glint_test.comp`, the kernel that runs the glint point query
    /// on test points.
    #[derive(Clone, Copy)]
    pub struct GlintTestPush<'a> {
        /// The infinite normal map.
        pub map: lazysolid_renderer::glint::GlintMapParams<'a>,
        /// Target points (vec2).
        pub points: DeviceAddress<'a>,
        /// 10 floats per point.
        pub results: DeviceAddress<'a>,
        /// Number of points.
        pub n: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render_test/glint_pndf_test.comp`, the kernel that runs the glint P-NDF
    /// and its sampling on test cases.
    #[derive(Clone, Copy)]
    pub struct GlintPndfTestPush<'a> {
        /// The infinite normal map.
        pub map: lazysolid_renderer::glint::GlintMapParams<'a>,
        /// Its range table.
        pub ranges: DeviceAddress<'a>,
        /// 12 floats per case.
        pub cases: DeviceAddress<'a>,
        /// 6 floats per case.
        pub results: DeviceAddress<'a>,
        /// Intrinsic roughness σ_r.
        pub sigma_r: f32,
        /// Number of cases.
        pub n: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render_test/glint_bsdf_test.comp`, the kernel that runs the glint
    /// material (`render/glint_bsdf.glsl`) on test cases.
    #[derive(Clone, Copy)]
    pub struct GlintBsdfTestPush<'a> {
        /// The `GlintRecord`s the cases index.
        pub records: DeviceAddress<'a>,
        /// 33 floats per case.
        pub cases: DeviceAddress<'a>,
        /// 24 floats per case.
        pub results: DeviceAddress<'a>,
        /// Number of cases.
        pub n: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render_test/image_test.comp`, the kernel that runs the image-texture
    /// lookup (`render/image.glsl`) on test queries.
    #[derive(Clone, Copy)]
    pub struct ImageTestPush<'a> {
        /// Three vec2 per query: uv and the footprint's axes.
        pub queries: DeviceAddress<'a>,
        /// One vec4 per query.
        pub results: DeviceAddress<'a>,
        /// The image's record.
        pub image: u32,
        /// Number of queries.
        pub n: u32,
    }
}

/// Every kernel of the workspace with the push block its dispatches use: the compute crate's,
/// the synthesizer's, the renderer's and the shading and glint test kernels.
pub fn push_registry() -> Vec<PushRegistration> {
    let mut all = lazysolid_compute::push_registry();
    all.extend(lazysolid_synth::push_registry());
    all.extend(lazysolid_renderer::push_registry());
    all.push(PushRegistration::of::<ShadingTestPush>(
        &kernels::render_test::SHADING_TEST,
    ));
    all.push(PushRegistration::of::<GlintTestPush>(
        &kernels::render_test::GLINT_TEST,
    ));
    all.push(PushRegistration::of::<GlintPndfTestPush>(
        &kernels::render_test::GLINT_PNDF_TEST,
    ));
    all.push(PushRegistration::of::<GlintBsdfTestPush>(
        &kernels::render_test::GLINT_BSDF_TEST,
    ));
    all.push(PushRegistration::of::<ImageTestPush>(
        &kernels::render_test::IMAGE_TEST,
    ));
    all
}
