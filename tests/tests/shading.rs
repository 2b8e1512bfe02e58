//! The shading library of the path tracer: every GLSL function (run by
//! `glsl/render_test/shading_test.comp`) against its CPU reference input by input, then the
//! statistics of the reference: energy conservation, pdfs that integrate to the probability of
//! sampling them, samples consistent with eval/pdf, normalized light and environment pdfs.
//!
//! GPU and CPU agree within a relative 1e-4 or an absolute 1e-5 ([`close`], [`close3`]). A sample
//! may differ when its inputs sit on a discontinuity (a lobe choice, the horizon) or where it is
//! ill-conditioned (grazing directions); such cases are recognized by nudging the inputs of the
//! CPU reference ([`sample_is_sensitive`]) and must stay under 1 %.

use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};
use lazysolid_compute::gpu::{DeviceRecords, Gpu, GpuBuffer, Kernel};
use lazysolid_renderer::scene::{Environment, Light};
use lazysolid_renderer::shader_constants::*;
use lazysolid_renderer::shading::reference as cpu;
use lazysolid_renderer::shading::{EnvironmentMap, GpuEnvironment, GpuLight, GpuMaterial};
use lazysolid_tests::kernels::render_test::SHADING_TEST;
use lazysolid_tests::shader_constants::*;
use lazysolid_tests::{rng, with_gpu, ShadingTestPush};
use rand::Rng;
use rayon::prelude::*;
use std::collections::HashMap;
use std::path::Path;

/// Floats written per case by the test kernel.
const RESULT_FLOATS: usize = 24;
/// Cases per material configuration, texture kind, light kind.
const CASES: usize = 4096;

/// One input of the test kernel (`ShadingCase` in `glsl/render_test/shading_test.comp`). Per mode:
/// - BSDF: a = albedo, b = wo, c = wi, d = u; results: eval (0..3), pdf (3), ok (4), wi (5..8),
///   weight (8..11), pdf (11), specular (12), has_smooth_lobe (13);
/// - texture: a = point; results: albedo (0..3);
/// - light: a = x, b.xy = u, c = ray origin and tmax, d = ray direction; results: ok (0),
///   wi (1..4), dist (4), radiance (5..8), pdf (8), hit (9), t (10), radiance (11..14),
///   light_pdf of the hit (14);
/// - environment: a = direction, b.xy = u; results: eval (0..3), pdf (3), ok (4), dir (5..8),
///   radiance (8..11), pdf (11);
/// - rng: a = pixel x, pixel y, sample index, seed (bits), b = u, c = normal; results: 8 random
///   numbers (0..8), cosine hemisphere (8..11), uniform sphere (11..14), disc (14..16),
///   frame t (16..19), b (19..22), pdf_cosine_hemisphere(b.z) (22).
#[repr(C)]
#[derive(Clone, Copy, Default, Pod, Zeroable)]
struct Case {
    m: GpuMaterial,
    l: GpuLight,
    a: [f32; 4],
    b: [f32; 4],
    c: [f32; 4],
    d: [f32; 4],
}

type Results = [f32; RESULT_FLOATS];

fn run(
    gpu: &Gpu,
    kernel: &Kernel,
    mode: u32,
    cases: &[Case],
    env: Option<&GpuEnvironment>,
) -> Vec<Results> {
    let input = GpuBuffer::from_slice(gpu, "shading cases", cases).unwrap();
    let output = GpuBuffer::<Results>::new(gpu, "shading results", cases.len()).unwrap();
    let params = [env.map(|e| e.params()).unwrap_or_default()];
    let params = DeviceRecords::new(gpu, "environment params", &params).unwrap();
    let push = ShadingTestPush {
        cases: input.address(),
        results: output.address(),
        environment: params.address(),
        mode,
        n: cases.len() as u32,
    };
    gpu.submit(|rec| rec.dispatch(kernel, kernel.groups_for(cases.len() as u64), &[], &push))
        .unwrap();
    output.read().unwrap()
}

/// Scalars within a relative 1e-4 or an absolute 1e-5.
fn close(a: f32, b: f32) -> bool {
    let d = (a - b).abs();
    d <= 1e-5 || d <= 1e-4 * a.abs().max(b.abs())
}

/// Vectors within a relative 1e-4 (of the longer one's length) or an absolute 1e-5: a unit
/// direction within 1e-4 radians.
fn close3(a: Vec3, b: Vec3) -> bool {
    let d = (a - b).length();
    d <= 1e-5 || d <= 1e-4 * a.length().max(b.length())
}

fn v3(r: &[f32]) -> Vec3 {
    Vec3::new(r[0], r[1], r[2])
}

fn pad(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

fn unit(r: &mut impl Rng) -> Vec3 {
    cpu::sample_uniform_sphere(Vec2::new(r.random(), r.random()))
}

fn random3(r: &mut impl Rng, lo: f32, hi: f32) -> Vec3 {
    Vec3::new(
        r.random_range(lo..hi),
        r.random_range(lo..hi),
        r.random_range(lo..hi),
    )
}

/// Material kinds and roughnesses covered: 0 and 0.02 are deltas (α below `GGX_MIN_ALPHA`).
const CONFIGS: &[(u32, f32)] = &[
    (MATERIAL_LAMBERTIAN, 0.0),
    (MATERIAL_CONDUCTOR, 0.0),
    (MATERIAL_CONDUCTOR, 0.02),
    (MATERIAL_CONDUCTOR, 0.2),
    (MATERIAL_CONDUCTOR, 0.5),
    (MATERIAL_CONDUCTOR, 1.0),
    (MATERIAL_PLASTIC, 0.0),
    (MATERIAL_PLASTIC, 0.2),
    (MATERIAL_PLASTIC, 0.5),
    (MATERIAL_PLASTIC, 1.0),
    (MATERIAL_DIELECTRIC, 0.0),
    (MATERIAL_DIELECTRIC, 0.2),
    (MATERIAL_DIELECTRIC, 0.5),
    (MATERIAL_DIELECTRIC, 1.0),
    (MATERIAL_EMISSIVE, 0.5),
];

/// A random material; a plastic's index is one of a few, so that its coat terms (a costly
/// quadrature) are computed once per index and roughness.
fn random_material(
    kind: u32,
    roughness: f32,
    r: &mut impl Rng,
    coats: &mut HashMap<(u32, u32), GpuMaterial>,
) -> GpuMaterial {
    let mut m = GpuMaterial {
        kind,
        roughness,
        color: if kind == MATERIAL_CONDUCTOR {
            random3(r, 0.1, 2.5).to_array()
        } else {
            random3(r, 0.05, 1.0).to_array()
        },
        k: random3(r, 0.0, 5.0).to_array(),
        ior: r.random_range(1.2..2.0),
        emission: random3(r, 0.0, 4.0).to_array(),
        ..Default::default()
    };
    if kind == MATERIAL_PLASTIC {
        m.ior = (m.ior * 4.0).round() / 4.0;
        let coat = coats
            .entry((roughness.to_bits(), m.ior.to_bits()))
            .or_insert_with(|| m.with_coat());
        m.coat_albedo = coat.coat_albedo;
        m.coat_internal = coat.coat_internal;
    }
    m
}

/// Lobe choice, validity and hemisphere of a CPU sample: what a discontinuity changes.
fn branch(s: &Option<cpu::BsdfSample>) -> (bool, bool, bool) {
    s.map_or((false, false, false), |s| (true, s.specular, s.wi.z > 0.0))
}

/// True when the CPU sample is not a smooth function of its inputs there: nudging `u` by 2e-4
/// changes its branch (a lobe choice, the horizon), or nudging `u` or `wo` by 1e-5 moves it
/// by more than the comparison's tolerance (an input error of ~100 ulps, amplified past 1e-4:
/// directions grazing the horizon, where G and the refraction Jacobian are steep). The GPU's
/// rounding differs from the CPU's, so there the two cannot be held to 1e-4.
fn sample_is_sensitive(m: &GpuMaterial, albedo: Vec3, wo: Vec3, u: Vec3) -> bool {
    let s = cpu::bsdf_sample(m, albedo, wo, u);
    let b = branch(&s);
    let same = |t: Option<cpu::BsdfSample>| match (s, t) {
        (Some(s), Some(t)) => {
            close3(s.wi, t.wi) && close3(s.weight, t.weight) && close(s.pdf, t.pdf)
        }
        _ => false,
    };
    (0..6).any(|k| {
        let sign = if k % 2 == 0 { -1.0 } else { 1.0 };
        let mut v = u;
        v[k / 2] = (v[k / 2] + sign * 2e-4).clamp(0.0, 0.999_999);
        let mut fine_u = u;
        fine_u[k / 2] = (fine_u[k / 2] + sign * 1e-5).clamp(0.0, 0.999_999);
        let mut fine_wo = wo;
        fine_wo[k / 2] += sign * 1e-5;
        branch(&cpu::bsdf_sample(m, albedo, wo, v)) != b
            || (s.is_some()
                && (!same(cpu::bsdf_sample(m, albedo, wo, fine_u))
                    || !same(cpu::bsdf_sample(m, albedo, fine_wo.normalize(), u))))
    })
}

#[test]
fn bsdfs_match_the_reference() {
    let mut r = rng(11);
    let mut cases = Vec::new();
    let mut coats = HashMap::new();
    for &(kind, roughness) in CONFIGS {
        for _ in 0..CASES {
            let mut wo = unit(&mut r);
            while wo.z.abs() < 0.02 {
                wo = unit(&mut r);
            }
            cases.push(Case {
                m: random_material(kind, roughness, &mut r, &mut coats),
                a: pad(random3(&mut r, 0.0, 1.0), 0.0),
                b: pad(wo, 0.0),
                c: pad(unit(&mut r), 0.0),
                d: pad(random3(&mut r, 0.0, 1.0), 0.0),
                ..Default::default()
            });
        }
    }
    let out = with_gpu(|gpu| {
        let kernel = gpu.kernel(&SHADING_TEST).unwrap();
        run(gpu, &kernel, SHADING_TEST_BSDF, &cases, None)
    });
    for (ci, &(kind, roughness)) in CONFIGS.iter().enumerate() {
        let mut failures = Vec::new();
        let mut sensitive = 0;
        let range = ci * CASES..(ci + 1) * CASES;
        for (c, g) in cases[range.clone()].iter().zip(&out[range]) {
            let (albedo, wo, wi, u) = (v3(&c.a), v3(&c.b), v3(&c.c), v3(&c.d));
            let eval = cpu::bsdf_eval(&c.m, albedo, wo, wi);
            let pdf = cpu::bsdf_pdf(&c.m, albedo, wo, wi);
            if !close3(eval, v3(&g[0..3])) || !close(pdf, g[3]) {
                failures.push(format!(
                    "eval/pdf wo {wo} wi {wi}: cpu {eval} {pdf}, gpu {:?}",
                    &g[0..4]
                ));
            }
            if cpu::bsdf_has_smooth_lobe(&c.m) != (g[13] == 1.0) {
                failures.push(format!("has_smooth_lobe differs for {:?}", c.m));
            }
            let s = cpu::bsdf_sample(&c.m, albedo, wo, u);
            let same = match s {
                Some(s) => {
                    g[4] == 1.0
                        && s.specular == (g[12] == 1.0)
                        && close3(s.wi, v3(&g[5..8]))
                        && close3(s.weight, v3(&g[8..11]))
                        && close(s.pdf, g[11])
                }
                None => g[4] == 0.0,
            };
            if !same {
                if sample_is_sensitive(&c.m, albedo, wo, u) {
                    sensitive += 1;
                } else {
                    failures.push(format!(
                        "sample wo {wo} u {u}: cpu {s:?}, gpu {:?}",
                        &g[4..13]
                    ));
                }
            }
        }
        assert!(
            failures.is_empty(),
            "kind {kind} roughness {roughness}: {} of {CASES} differ, e.g. {:#?}",
            failures.len(),
            &failures[..failures.len().min(5)]
        );
        assert!(
            sensitive <= CASES / 100,
            "kind {kind} roughness {roughness}: {sensitive} samples at discontinuities"
        );
    }
}

#[test]
fn solid_textures_and_random_numbers_match_the_reference() {
    let mut r = rng(12);
    let mut textures = Vec::new();
    for kind in [TEXTURE_NONE, TEXTURE_MARBLE, TEXTURE_WOOD, TEXTURE_CHECKER] {
        for _ in 0..CASES {
            let m = GpuMaterial {
                color: random3(&mut r, 0.0, 1.0).to_array(),
                texture_kind: kind,
                tex_color_a: random3(&mut r, 0.0, 1.0).to_array(),
                tex_color_b: random3(&mut r, 0.0, 1.0).to_array(),
                tex_scale: r.random_range(0.5..8.0),
                ..Default::default()
            };
            textures.push(Case {
                m,
                a: pad(random3(&mut r, -2.0, 2.0), 0.0),
                ..Default::default()
            });
        }
    }
    let rng_cases: Vec<Case> = (0..CASES)
        .map(|i| {
            let bits = [
                r.random_range(0..4096u32),
                r.random_range(0..4096u32),
                i as u32,
                r.random(),
            ];
            Case {
                a: bits.map(f32::from_bits),
                b: pad(random3(&mut r, 0.0, 1.0), 0.0),
                c: pad(unit(&mut r), 0.0),
                ..Default::default()
            }
        })
        .collect();
    let (tex_out, rng_out) = with_gpu(|gpu| {
        let kernel = gpu.kernel(&SHADING_TEST).unwrap();
        (
            run(gpu, &kernel, SHADING_TEST_TEXTURE, &textures, None),
            run(gpu, &kernel, SHADING_TEST_RNG, &rng_cases, None),
        )
    });
    for (c, g) in textures.iter().zip(&tex_out) {
        let cpu = cpu::solid_texture_albedo(&c.m, v3(&c.a));
        assert!(
            close3(cpu, v3(&g[0..3])),
            "texture {} at {:?} scale {}: cpu {cpu}, gpu {:?}",
            c.m.texture_kind,
            c.a,
            c.m.tex_scale,
            &g[0..3]
        );
        if c.m.texture_kind == TEXTURE_CHECKER {
            assert_eq!(cpu, v3(&g[0..3]), "the checker is exact");
        }
    }
    for (c, g) in rng_cases.iter().zip(&rng_out) {
        let bits = c.a.map(f32::to_bits);
        let mut state = cpu::rng_init([bits[0], bits[1]], bits[2], bits[3]);
        let numbers: Vec<f32> = (0..8).map(|_| cpu::rng_next(&mut state)).collect();
        assert_eq!(numbers, g[0..8].to_vec(), "random numbers are bit-exact");
        assert!(numbers.iter().all(|x| (0.0..1.0).contains(x)));
        let u = Vec2::new(c.b[0], c.b[1]);
        assert!(close3(cpu::sample_cosine_hemisphere(u), v3(&g[8..11])));
        assert!(close3(cpu::sample_uniform_sphere(u), v3(&g[11..14])));
        let disk = cpu::sample_concentric_disk(u);
        assert!(close(disk.x, g[14]) && close(disk.y, g[15]));
        let n = v3(&c.c);
        let (t, b) = cpu::make_frame(n);
        assert!(close3(t, v3(&g[16..19])) && close3(b, v3(&g[19..22])));
        assert!((t.cross(b) - n).length() < 1e-5 && t.dot(n).abs() < 1e-5);
        assert!(close(cpu::pdf_cosine_hemisphere(c.b[2]), g[22]));
    }
}

/// A random light of kind 0 (sphere), 1 (one-sided quad) or 2 (two-sided quad).
fn random_light(kind: usize, r: &mut impl Rng) -> GpuLight {
    let radiance = random3(r, 0.5, 10.0);
    let light = if kind == 0 {
        Light::Sphere {
            center: random3(r, -1.0, 1.0),
            radius: r.random_range(0.1..1.0),
            radiance,
        }
    } else {
        Light::Quad {
            corner: random3(r, -1.0, 1.0),
            edge_u: random3(r, -1.5, 1.5),
            edge_v: random3(r, -1.5, 1.5),
            radiance,
            two_sided: kind == 2,
        }
    };
    GpuLight::from(&light)
}

/// A point near the light (a sphere grown by 20 %, a quad's parameters in [-0.2, 1.2]).
fn near_light(l: &GpuLight, r: &mut impl Rng) -> Vec3 {
    if l.kind == LIGHT_SPHERE {
        Vec3::from(l.p) + unit(r) * l.radius * r.random_range(0.0..1.2)
    } else {
        Vec3::from(l.p)
            + r.random_range(-0.2..1.2) * Vec3::from(l.u)
            + r.random_range(-0.2..1.2) * Vec3::from(l.v)
    }
}

#[test]
fn lights_match_the_reference() {
    let mut r = rng(13);
    let mut cases = Vec::new();
    for kind in 0..3 {
        for _ in 0..CASES {
            let l = random_light(kind, &mut r);
            let o = random3(&mut r, -3.0, 3.0);
            let target = near_light(&l, &mut r);
            let tmax = if r.random_bool(0.5) {
                1e30
            } else {
                (target - o).length() * r.random_range(0.5..1.5)
            };
            cases.push(Case {
                l,
                a: pad(random3(&mut r, -3.0, 3.0), 0.0),
                b: pad(random3(&mut r, 0.0, 1.0), 0.0),
                c: pad(o, tmax),
                d: pad((target - o).normalize(), 0.0),
                ..Default::default()
            });
        }
    }
    let out = with_gpu(|gpu| {
        let kernel = gpu.kernel(&SHADING_TEST).unwrap();
        run(gpu, &kernel, SHADING_TEST_LIGHT, &cases, None)
    });
    let mut edges = 0;
    for (c, g) in cases.iter().zip(&out) {
        let (x, u) = (v3(&c.a), Vec2::new(c.b[0], c.b[1]));
        match cpu::light_sample(&c.l, x, u) {
            Some(s) => assert!(
                g[0] == 1.0
                    && close3(s.wi, v3(&g[1..4]))
                    && close(s.dist, g[4])
                    && close3(s.radiance, v3(&g[5..8]))
                    && close(s.pdf, g[8]),
                "light {:?} from {x} u {u}: cpu {s:?}, gpu {:?}",
                c.l,
                &g[0..9]
            ),
            None => assert_eq!(g[0], 0.0, "light {:?} from {x} u {u}", c.l),
        }
        let (o, d, tmax) = (v3(&c.c), v3(&c.d), c.c[3]);
        let hit = cpu::light_intersect(&c.l, o, d, tmax);
        let same = match hit {
            Some(h) => {
                g[9] == 1.0
                    && close(h.t, g[10])
                    && close3(h.radiance, v3(&g[11..14]))
                    && close(cpu::light_pdf(&c.l, o, d, h.t), g[14])
            }
            None => g[9] == 0.0,
        };
        if !same {
            // A ray grazing the silhouette or the end of the segment may go either way.
            let nudged = (0..6).any(|k| {
                let mut e = Vec3::ZERO;
                e[k / 2] = if k % 2 == 0 { -1e-4 } else { 1e-4 };
                cpu::light_intersect(&c.l, o, (d + e).normalize(), tmax).is_some() != hit.is_some()
            });
            assert!(
                nudged,
                "ray {o} {d} tmax {tmax} to {:?}: cpu {hit:?}, gpu {:?}",
                c.l,
                &g[9..15]
            );
            edges += 1;
        }
    }
    assert!(edges <= cases.len() / 100, "{edges} rays on light edges");
}

/// A 64x32 map: a smooth sky, one black row, a small bright coloured sun.
fn test_map(rotation_deg: f32) -> EnvironmentMap {
    let (w, h) = (64u32, 32u32);
    let mut texels = Vec::new();
    for y in 0..h {
        for x in 0..w {
            let sky = if y == 20 {
                Vec3::ZERO
            } else {
                Vec3::new(0.2, 0.3, 0.5)
                    * (1.0 + (x as f32 * 0.3).sin() * 0.5)
                    * (1.0 - y as f32 / h as f32)
            };
            let sun = if (10..13).contains(&x) && (5..7).contains(&y) {
                Vec3::new(40.0, 30.0, 20.0)
            } else {
                Vec3::ZERO
            };
            texels.extend_from_slice(&(sky + sun).to_array());
        }
    }
    EnvironmentMap::from_texels(Path::new("test-map"), w, h, texels, 1.5, rotation_deg).unwrap()
}

#[test]
fn environments_match_the_reference() {
    let maps = [
        test_map(37.0),
        EnvironmentMap::constant(Vec3::new(0.3, 0.5, 0.7)),
    ];
    let mut r = rng(14);
    let cases: Vec<Case> = (0..2 * CASES)
        .map(|_| Case {
            a: pad(unit(&mut r), 0.0),
            b: pad(random3(&mut r, 0.0, 1.0), 0.0),
            ..Default::default()
        })
        .collect();
    let outs: Vec<Vec<Results>> = with_gpu(|gpu| {
        let kernel = gpu.kernel(&SHADING_TEST).unwrap();
        maps.iter()
            .map(|map| {
                let env = GpuEnvironment::new(gpu, map).unwrap();
                run(gpu, &kernel, SHADING_TEST_ENVIRONMENT, &cases, Some(&env))
            })
            .collect()
    });
    for (map, out) in maps.iter().zip(&outs) {
        let mut edges = 0;
        for (c, g) in cases.iter().zip(out) {
            let dir = v3(&c.a);
            let (eval, pdf) = (cpu::env_eval(map, dir), cpu::env_pdf(map, dir));
            if !(close3(eval, v3(&g[0..3])) && close(pdf, g[3])) {
                // Only a direction on a texel boundary may land in another texel.
                let nudged = (0..6).any(|k| {
                    let mut e = Vec3::ZERO;
                    e[k / 2] = if k % 2 == 0 { -1e-4 } else { 1e-4 };
                    cpu::env_eval(map, (dir + e).normalize()) != eval
                });
                assert!(nudged, "{dir}: cpu {eval} {pdf}, gpu {:?}", &g[0..4]);
                edges += 1;
            }
            let u = Vec2::new(c.b[0], c.b[1]);
            match cpu::env_sample(map, u) {
                Some(s) => assert!(
                    g[4] == 1.0
                        && close3(s.dir, v3(&g[5..8]))
                        && close3(s.radiance, v3(&g[8..11]))
                        && close(s.pdf, g[11]),
                    "u {u}: cpu {s:?}, gpu {:?}",
                    &g[4..12]
                ),
                None => assert_eq!(g[4], 0.0),
            }
        }
        assert!(
            edges <= cases.len() / 100,
            "{edges} directions on texel edges"
        );
    }
}

// ---- Statistics of the CPU reference ----

/// `n` random numbers in [0, 1)^3 from the renderer's own generator.
fn stream(seed: u32, n: usize) -> Vec<Vec3> {
    let mut s = cpu::rng_init([seed, 7], 0, 2024);
    (0..n)
        .map(|_| {
            let v = cpu::rng_next2(&mut s);
            Vec3::new(v.x, v.y, cpu::rng_next(&mut s))
        })
        .collect()
}

/// A direction at `cos_theta` from +z (negative: below), at a fixed irrational azimuth.
fn direction(cos_theta: f32, azimuth: f32) -> Vec3 {
    let s = (1.0 - cos_theta * cos_theta).sqrt();
    Vec3::new(s * azimuth.cos(), s * azimuth.sin(), cos_theta)
}

fn mat(kind: u32, roughness: f32, color: Vec3) -> GpuMaterial {
    GpuMaterial {
        kind,
        roughness,
        color: color.to_array(),
        k: [3.0, 2.5, 2.0],
        ior: 1.5,
        ..Default::default()
    }
    .with_coat()
}

const COSINES: &[f32] = &[1.0, 0.8, 0.5, 0.2, 0.05, -0.05, -0.3, -0.7, -1.0];

#[test]
fn bsdfs_conserve_energy_and_samples_match_eval() {
    let white = Vec3::ONE;
    // (material, albedo, lossless: E[weight] must be 1).
    let configs = [
        (mat(MATERIAL_LAMBERTIAN, 0.0, white), true),
        (mat(MATERIAL_DIELECTRIC, 0.0, white), true),
        (mat(MATERIAL_PLASTIC, 0.0, white), false),
        (mat(MATERIAL_PLASTIC, 0.3, white), false),
        (mat(MATERIAL_PLASTIC, 1.0, white), false),
        (
            mat(MATERIAL_CONDUCTOR, 0.0, Vec3::new(0.2, 0.9, 1.1)),
            false,
        ),
        (
            mat(MATERIAL_CONDUCTOR, 0.3, Vec3::new(0.2, 0.9, 1.1)),
            false,
        ),
        (
            mat(MATERIAL_CONDUCTOR, 1.0, Vec3::new(0.2, 0.9, 1.1)),
            false,
        ),
        (mat(MATERIAL_DIELECTRIC, 0.1, white), false),
        (mat(MATERIAL_DIELECTRIC, 0.5, white), false),
        (mat(MATERIAL_DIELECTRIC, 1.0, white), false),
    ];
    let n = 20_000;
    let jobs: Vec<(usize, usize)> = (0..configs.len())
        .flat_map(|c| (0..COSINES.len()).map(move |w| (c, w)))
        .collect();
    jobs.par_iter().for_each(|&(ci, wi_index)| {
        let (m, lossless) = configs[ci];
        let albedo = Vec3::from(m.color);
        let wo = direction(COSINES[wi_index], 0.7 + ci as f32);
        let what = format!("{m:?} wo {wo}");
        let mut sum = Vec3::ZERO;
        let mut sum2 = Vec3::ZERO;
        for u in stream((ci * 100 + wi_index) as u32, n) {
            let Some(s) = cpu::bsdf_sample(&m, albedo, wo, u) else {
                continue;
            };
            assert!(
                s.weight.is_finite() && s.weight.min_element() >= 0.0,
                "{what}: {s:?}"
            );
            sum += s.weight;
            sum2 += s.weight * s.weight;
            if !s.specular {
                let pdf = cpu::bsdf_pdf(&m, albedo, wo, s.wi);
                let eval = cpu::bsdf_eval(&m, albedo, wo, s.wi);
                let expect = eval / pdf;
                assert!(
                    (pdf - s.pdf).abs() <= 1e-3 * pdf.max(s.pdf),
                    "{what}: sampled pdf {} but bsdf_pdf {pdf} at {}",
                    s.pdf,
                    s.wi
                );
                assert!(
                    (expect - s.weight).abs().max_element() <= 1e-5 + 1e-3 * expect.max_element(),
                    "{what}: weight {} but eval/pdf {expect} at {}",
                    s.weight,
                    s.wi
                );
            }
        }
        let mean = sum / n as f32;
        let stderr = ((sum2 / n as f32 - mean * mean).max(Vec3::ZERO) / n as f32)
            .sqrt()
            .max_element();
        assert!(
            mean.max_element() <= 1.0 + 4.0 * stderr + 1e-4,
            "{what}: E[weight] = {mean} exceeds 1 (stderr {stderr})"
        );
        if lossless {
            assert!(
                (mean - Vec3::ONE).abs().max_element() <= 0.01,
                "{what}: lossless but E[weight] = {mean}"
            );
        }
    });
}

/// Mean BSDF sample weight from `wo`: the directional albedo, delta lobes included. The
/// direction's two numbers lie on an `n` × `n` stratified grid; the lobe choice is random (a
/// stratified choice would bias the mixture's proportions).
fn directional_albedo(m: &GpuMaterial, wo: Vec3, n: usize) -> f64 {
    let albedo = Vec3::from(m.color);
    let lobes = stream(n as u32, n * n);
    let sum: f64 = (0..n * n)
        .into_par_iter()
        .map(|i| {
            let u = Vec3::new(
                ((i % n) as f32 + 0.5) / n as f32,
                ((i / n) as f32 + 0.5) / n as f32,
                lobes[i].z,
            );
            cpu::bsdf_sample(m, albedo, wo, u).map_or(0.0, |s| s.weight.x as f64)
        })
        .sum();
    sum / (n * n) as f64
}

/// Plastic with a white base reflects everything: the coat's reflectance plus what the base
/// returns through it: within 1 % at every angle, smooth or rough (measured: 0.05 % smooth,
/// 0.6 % at most rough, at grazing where the coat's albedo table is interpolated). The single-scattering GGX interface loses
/// energy at grazing angles and high roughness (printed: a rough dielectric's R + T); the
/// plastic hands that energy to the base instead of losing it.
#[test]
fn white_plastic_reflects_everything() {
    let cosines = [1.0f32, 0.8, 0.5, 0.3, 0.2, 0.1, 0.05];
    for roughness in [0.0f32, 0.1, 0.2, 0.3, 0.5] {
        let bound = 0.01;
        let plastic = mat(MATERIAL_PLASTIC, roughness, Vec3::ONE);
        let interface = mat(MATERIAL_DIELECTRIC, roughness, Vec3::ONE);
        let mut line = format!("roughness {roughness}:");
        for &cos in &cosines {
            let wo = direction(cos, 0.4);
            let a = directional_albedo(&plastic, wo, 256);
            let loss = 1.0 - directional_albedo(&interface, wo, 256);
            line += &format!(" cos {cos}: {a:.4} (interface loses {loss:.4});");
            assert!(
                (a - 1.0).abs() <= bound,
                "white plastic roughness {roughness} at cos {cos} reflects {a}, bound {bound}"
            );
        }
        println!("{line}");
    }
}

/// ∫ f over the sphere from a stratified grid of `k × k` uniform directions.
fn sphere_integral(k: usize, f: impl Fn(Vec3) -> f32 + Sync) -> f32 {
    let sum: f64 = (0..k * k)
        .into_par_iter()
        .map(|i| {
            // Jitter from a fixed hash keeps the estimate deterministic.
            let mut s = cpu::rng_init([i as u32, 3], 1, 99);
            let j = cpu::rng_next2(&mut s);
            let u = Vec2::new(
                ((i % k) as f32 + j.x) / k as f32,
                ((i / k) as f32 + j.y) / k as f32,
            );
            f(cpu::sample_uniform_sphere(u)) as f64
        })
        .sum();
    (sum * 4.0 * std::f64::consts::PI / (k * k) as f64) as f32
}

#[test]
fn bsdf_pdfs_integrate_to_the_smooth_sampling_probability() {
    let albedo = Vec3::new(0.7, 0.5, 0.3);
    let configs = [
        mat(MATERIAL_LAMBERTIAN, 0.0, albedo),
        mat(MATERIAL_CONDUCTOR, 0.5, albedo),
        mat(MATERIAL_CONDUCTOR, 1.0, albedo),
        mat(MATERIAL_PLASTIC, 0.0, albedo),
        mat(MATERIAL_PLASTIC, 0.5, albedo),
        mat(MATERIAL_PLASTIC, 1.0, albedo),
        mat(MATERIAL_DIELECTRIC, 0.5, albedo),
        mat(MATERIAL_DIELECTRIC, 1.0, albedo),
    ];
    for m in &configs {
        for &cos in &[0.9f32, 0.4, -0.6] {
            let wo = direction(cos, 2.1);
            let integral = sphere_integral(400, |wi| cpu::bsdf_pdf(m, albedo, wo, wi));
            let n = 100_000;
            let smooth = stream(77, n)
                .par_iter()
                .filter(|&&u| cpu::bsdf_sample(m, albedo, wo, u).is_some_and(|s| !s.specular))
                .count() as f32
                / n as f32;
            assert!(
                (integral - smooth).abs() <= 0.02 * smooth.max(0.05),
                "{m:?} wo {wo}: ∫pdf = {integral} but non-delta samples succeed with {smooth}"
            );
        }
    }
}

#[test]
fn light_pdfs_integrate_to_one_and_match_sampling() {
    let lights = [
        Light::Sphere {
            center: Vec3::new(0.0, 3.0, 0.5),
            radius: 1.0,
            radiance: Vec3::ONE,
        },
        Light::Quad {
            corner: Vec3::new(-1.0, 2.0, -0.5),
            edge_u: Vec3::new(2.0, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 1.5),
            radiance: Vec3::ONE,
            two_sided: false,
        },
        Light::Quad {
            corner: Vec3::new(-1.0, -1.0, -0.5),
            edge_u: Vec3::new(2.0, 0.3, 0.0),
            edge_v: Vec3::new(0.0, 0.5, 1.5),
            radiance: Vec3::ONE,
            two_sided: true,
        },
    ];
    let x = Vec3::new(0.2, 0.1, 0.3);
    for light in &lights {
        let l = GpuLight::from(light);
        let integral = sphere_integral(600, |d| {
            cpu::light_intersect(&l, x, d, f32::INFINITY)
                .map_or(0.0, |h| cpu::light_pdf(&l, x, d, h.t))
        });
        assert!(
            (integral - 1.0).abs() < 0.02,
            "{light:?}: ∫pdf = {integral}"
        );
        for u in stream(5, 2000) {
            let s = cpu::light_sample(&l, x, Vec2::new(u.x, u.y))
                .unwrap_or_else(|| panic!("{light:?} cannot be sampled from {x}"));
            let hit = cpu::light_intersect(&l, x, s.wi, f32::INFINITY)
                .unwrap_or_else(|| panic!("{light:?}: sampled {} misses", s.wi));
            assert!(
                (hit.t - s.dist).abs() < 1e-3 * s.dist,
                "{light:?}: {hit:?} {s:?}"
            );
            let pdf = cpu::light_pdf(&l, x, s.wi, s.dist);
            assert!(
                (pdf - s.pdf).abs() < 1e-3 * pdf,
                "{light:?}: {pdf} vs {s:?}"
            );
        }
    }
}

#[test]
fn environment_pdf_integrates_to_one_and_matches_sampling() {
    let map = test_map(-75.0);
    let integral = sphere_integral(600, |d| cpu::env_pdf(&map, d));
    assert!((integral - 1.0).abs() < 0.02, "∫env_pdf = {integral}");
    // Sampled texels follow the tables: counts within 5 sigma of N × probability.
    let (w, h) = (map.width as usize, map.height as usize);
    let n = 200_000;
    let mut counts = vec![0usize; w * h];
    let mut mismatched = 0;
    for u in stream(9, n) {
        let s = cpu::env_sample(&map, Vec2::new(u.x, u.y)).expect("the map has light");
        let pdf = cpu::env_pdf(&map, s.dir);
        if (pdf - s.pdf).abs() > 1e-3 * pdf.max(s.pdf) || cpu::env_eval(&map, s.dir) != s.radiance {
            // Only a sample on a texel boundary may be read back from a neighbour.
            mismatched += 1;
        }
        let m = &map.marginal_cdf;
        let r = m.partition_point(|&c| c <= u.y) - 1;
        let cdf = &map.conditional_cdf[r * (w + 1)..(r + 1) * (w + 1)];
        let c = cdf.partition_point(|&v| v <= u.x) - 1;
        counts[r * w + c] += 1;
    }
    assert!(
        mismatched <= n / 200,
        "{mismatched} samples disagree with env_pdf/env_eval"
    );
    for (i, &count) in counts.iter().enumerate() {
        let p = map.pdf[i] as f64 / (w * h) as f64;
        let expect = p * n as f64;
        assert!(
            (count as f64 - expect).abs() <= 5.0 * expect.sqrt() + 1.0,
            "texel {i}: {count} samples, {expect} expected"
        );
        if map.pdf[i] == 0.0 {
            assert_eq!(count, 0, "texel {i} has no light but was sampled");
        }
    }
    // A constant environment samples the sphere uniformly.
    let constant = EnvironmentMap::constant(Vec3::splat(0.5));
    let integral = sphere_integral(100, |d| cpu::env_pdf(&constant, d));
    assert!((integral - 1.0).abs() < 1e-3);
    assert!(cpu::env_sample(&EnvironmentMap::constant(Vec3::ZERO), Vec2::splat(0.5)).is_none());
}

#[test]
fn exr_maps_load_and_upload_and_errors_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sky.exr");
    let (w, h) = (8u32, 4u32);
    let texels: Vec<f32> = (0..w * h * 3).map(|i| (i % 7) as f32 * 0.25).collect();
    image::Rgb32FImage::from_raw(w, h, texels.clone())
        .unwrap()
        .save(&path)
        .unwrap();
    let env = Environment::LatLong {
        path: path.clone(),
        intensity: 2.0,
        rotation_deg: 10.0,
    };
    let map = EnvironmentMap::from_scene(&env).unwrap();
    assert_eq!((map.width, map.height), (w, h));
    assert_eq!(map.texels, texels);
    with_gpu(|gpu| {
        let uploaded = GpuEnvironment::from_scene(gpu, &env).unwrap();
        let p = uploaded.params();
        assert_eq!(
            (p.kind, p.width, p.height, p.sampleable),
            (ENVIRONMENT_LATLONG, w, h, 1)
        );
        assert_eq!(p.intensity, 2.0);
        assert_eq!(uploaded.bytes(), 4 * (3 * 32 + 32 + 5 + 4 * 9));
        let missing = dir.path().join("missing.exr");
        let e = GpuEnvironment::from_scene(
            gpu,
            &Environment::LatLong {
                path: missing.clone(),
                intensity: 1.0,
                rotation_deg: 0.0,
            },
        )
        .err()
        .unwrap()
        .to_string();
        assert!(e.contains(&missing.display().to_string()), "{e}");
    });
    let garbage = dir.path().join("garbage.exr");
    std::fs::write(&garbage, b"not an image").unwrap();
    let e = EnvironmentMap::load(&garbage, 1.0, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("garbage.exr"), "{e}");
    let e = EnvironmentMap::load(&path, f32::NAN, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("sky.exr") && e.contains("intensity"), "{e}");
}
