//! Texture synthesis: the GPU synthesizer against the CPU reference (every level, exactly),
//! spatial determinism of windows, the zero-jitter tiling, the energy metric on known answers,
//! and the errors of bad exemplars.

use lazysolid_synth::{
    analyze, default_passes_for, energy_cpu, hash4, histogram_distance, pack, period_repetition,
    plan_regions, synthesize_cpu, unpack, AnalysisParams, EnergyKernel, Exemplar, ExemplarAnalysis,
    GpuSynthesizer, Region, SynthError, SynthParams, MAX_PERIOD_PENALTY, MIN_EXEMPLAR_SIDE,
    REPETITION_TOLERANCE,
};
use lazysolid_tests::{asset_exemplar, exemplar_crop, with_gpu};
use std::sync::OnceLock;

/// GIMP's 64² leather pattern and its analysis, shared by the tests.
fn leather() -> &'static (Exemplar, ExemplarAnalysis) {
    static CELL: OnceLock<(Exemplar, ExemplarAnalysis)> = OnceLock::new();
    CELL.get_or_init(|| {
        let exemplar = Exemplar::load(&asset_exemplar("leather.pat")).unwrap();
        let analysis = analyze(&exemplar, &AnalysisParams::default()).unwrap();
        (exemplar, analysis)
    })
}

/// A 32×40 crop of GIMP's terra pattern (not square, not a power of two), analysed with k = 3.
fn terra_crop() -> &'static (Exemplar, ExemplarAnalysis) {
    static CELL: OnceLock<(Exemplar, ExemplarAnalysis)> = OnceLock::new();
    CELL.get_or_init(|| {
        let exemplar = exemplar_crop("terra.pat", 0, 0, 32, 40);
        let params = AnalysisParams {
            k: 3,
            ..AnalysisParams::default()
        };
        let analysis = analyze(&exemplar, &params).unwrap();
        (exemplar, analysis)
    })
}

fn window(x: i32, y: i32, w: u32, h: u32) -> Region {
    Region {
        origin: [x, y],
        size: [w, h],
    }
}

#[test]
fn gimp_patterns_decode() {
    let (leather, _) = leather();
    assert_eq!((leather.width, leather.height), (64, 64));
    let walnut = Exemplar::load(&asset_exemplar("walnut.pat")).unwrap();
    assert_eq!((walnut.width, walnut.height), (128, 128));
    // Real texture, not a decoding artefact: many distinct colours.
    let mut colours = leather.rgb.clone();
    colours.sort();
    colours.dedup();
    assert!(colours.len() > 500, "{} colours", colours.len());
}

#[test]
fn gpu_equals_cpu_on_every_level() {
    for (case, (_, analysis)) in [leather(), terra_crop()].into_iter().enumerate() {
        let levels = analysis.levels.len() as u32;
        // Case 0: the default schedule (its layout levels uncorrected); case 1: different pass
        // counts per level (so per-level padding), one level without correction.
        let passes = if case == 0 {
            let passes = default_passes_for(levels, analysis.width.min(analysis.height));
            assert!(passes[0] == 0 && passes[passes.len() - 2] > 0, "{passes:?}");
            passes
        } else {
            (0..levels).map(|l| [3, 0, 1, 2][l as usize % 4]).collect()
        };
        // Case 0 ranks candidates that span a period last (the largest penalty), case 1 adds
        // a penalty comparable to the distances, so that it trades against them.
        let penalty = if case == 0 { MAX_PERIOD_PENALTY } else { 3000 };
        let params = SynthParams::new(levels, 7 + case as u32, &passes, &[0.6])
            .unwrap()
            .with_period_penalty(penalty)
            .unwrap();
        let win = window(-13, 29, 40, 24);
        let cpu = synthesize_cpu(analysis, &params, win).unwrap();
        let gpu = with_gpu(|gpu| {
            let synth = GpuSynthesizer::new(gpu, analysis).unwrap();
            synth
                .synthesize(analysis, &params, win, true, &mut |_| {})
                .unwrap()
        });
        assert_eq!(cpu.levels.len(), levels as usize);
        for (l, (c, g)) in cpu.levels.iter().zip(&gpu.levels).enumerate() {
            assert_eq!(c.region, g.region, "case {case} level {l}");
            let differ = c
                .coords
                .iter()
                .zip(&g.coords)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differ, 0,
                "case {case} level {l}: {differ} coordinates differ"
            );
        }
        // Correction did something: the output is neither the tiling nor constant.
        let coords = cpu.window_coords();
        let tiling = (0..win.pixels()).filter(|&i| {
            let (x, y) = unpack(coords[i]);
            let px = (win.origin[0] + (i % 40) as i32).rem_euclid(analysis.width as i32) as u32;
            let py = (win.origin[1] + (i / 40) as i32).rem_euclid(analysis.height as i32) as u32;
            (x, y) == (px, py)
        });
        assert!(
            tiling.count() < win.pixels() / 2,
            "case {case}: mostly the tiling"
        );
    }
}

#[test]
fn overlapping_windows_agree() {
    let (_, analysis) = leather();
    let params = SynthParams::new(analysis.levels.len() as u32, 99, &[2], &[0.5]).unwrap();
    let (a, b) = (window(0, 0, 80, 64), window(37, -21, 64, 72));
    let (sa, sb) = with_gpu(|gpu| {
        let synth = GpuSynthesizer::new(gpu, analysis).unwrap();
        let run = |w| {
            synth
                .synthesize(analysis, &params, w, false, &mut |_| {})
                .unwrap()
        };
        (run(a), run(b))
    });
    let (ca, cb) = (sa.window_coords(), sb.window_coords());
    let mut compared = 0;
    for y in 0..43 {
        for x in 37..80 {
            let ia = y as usize * 80 + x as usize;
            let ib = (y + 21) as usize * 64 + (x - 37) as usize;
            assert_eq!(ca[ia], cb[ib], "absolute pixel ({x}, {y})");
            compared += 1;
        }
    }
    assert_eq!(compared, 43 * 43);
    // The CPU reference agrees with a third, shifted window too.
    let c = synthesize_cpu(analysis, &params, window(40, 10, 8, 8)).unwrap();
    let cc = c.window_coords();
    for y in 0..8 {
        for x in 0..8 {
            assert_eq!(cc[y * 8 + x], ca[(10 + y) * 80 + 40 + x]);
        }
    }
}

#[test]
fn zero_jitter_reproduces_the_tiling() {
    // Without the period penalty: the tiling is the one layout it exists to discourage.
    for (_, analysis) in [leather(), terra_crop()] {
        let params = SynthParams::new(analysis.levels.len() as u32, 5, &[2], &[0.0])
            .unwrap()
            .with_period_penalty(0)
            .unwrap();
        let win = window(-100, 55, 50, 30);
        let gpu = with_gpu(|gpu| {
            let synth = GpuSynthesizer::new(gpu, analysis).unwrap();
            synth
                .synthesize(analysis, &params, win, false, &mut |_| {})
                .unwrap()
        });
        for (i, c) in gpu.window_coords().into_iter().enumerate() {
            let px = win.origin[0] + (i % 50) as i32;
            let py = win.origin[1] + (i / 50) as i32;
            let expected = (
                px.rem_euclid(analysis.width as i32) as u32,
                py.rem_euclid(analysis.height as i32) as u32,
            );
            assert_eq!(unpack(c), expected, "pixel ({px}, {py})");
        }
    }
}

/// Coordinates of a `w`×`h` output made of 16×16 blocks, each a copy of a 32×40 exemplar
/// shifted by `shift(block x, block y)`.
fn block_copies(w: u32, h: u32, shift: impl Fn(u32, u32) -> (u32, u32)) -> Vec<u32> {
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (sx, sy) = shift(x / 16, y / 16);
            pack((x + sx) % 32, (y + sy) % 40)
        })
        .collect()
}

#[test]
fn period_repetition_separates_tilings_from_independent_patches() {
    let (w, h) = (200, 150);
    let measure = |c: &[u32]| period_repetition(c, w, h, 32, 40);
    // The plain tiling, and a near-tiling shifted by up to the tolerance per block, repeat fully.
    assert_eq!(measure(&block_copies(w, h, |_, _| (0, 0))), 1.0);
    let t = REPETITION_TOLERANCE;
    assert_eq!(
        measure(&block_copies(w, h, |bx, by| ((bx + by) % 2 * t, 0))),
        1.0
    );
    // Blocks shifted by hashed offsets repeat by chance only: (2·4 + 1)² / (32·40) ≈ 6 %.
    let random = block_copies(w, h, |bx, by| {
        (hash4(bx, by, 1, 2) % 32, hash4(bx, by, 3, 4) % 40)
    });
    let r = measure(&random);
    assert!(r < 0.15, "independent patches: {r}");
    // No pair one period apart fits: 0, not a division by zero.
    assert_eq!(period_repetition(&vec![0; 31 * 39], 31, 39, 32, 40), 0.0);
}

#[test]
fn padding_follows_the_formula() {
    // L = 6, two passes: c = 8 at every level, parents cover floor/ceil halves.
    let regions = plan_regions(window(-5, 3, 20, 10), &[2; 7]);
    assert_eq!(regions.len(), 7);
    assert_eq!(regions[6], window(-13, -5, 36, 26));
    // Parents of x in -13..23 are -7..12, grown by 8: -15..20.
    assert_eq!(regions[5].origin[0], -15);
    assert_eq!(regions[5].size[0], 35);
    // Per-level passes: level 6 with one pass grows by 4, level 5 with three by 12.
    let regions = plan_regions(window(-5, 3, 20, 10), &[2, 2, 2, 2, 2, 3, 1]);
    assert_eq!(regions[6], window(-9, -1, 28, 18));
    // Parents of x in -9..19 are -5..10, grown by 12: -17..22.
    assert_eq!(regions[5].origin[0], -17);
    assert_eq!(regions[5].size[0], 39);
}

#[test]
fn energy_known_answers() {
    let (leather, _) = leather();
    // The exemplar scores 0 against itself.
    let cpu = energy_cpu(leather, &leather.rgb, 64, 64, 64).unwrap();
    assert_eq!(cpu.len(), 64);
    assert!(cpu.iter().all(|&e| e == 0));
    // A constant image against a two-colour exemplar: the best neighbourhood is all of the
    // nearer colour, 49 · min(|C − A|², |C − B|²) = 49 · 5000.
    let (a, b, c) = ([10u8, 20, 30], [200u8, 100, 50], [60u8, 60, 60]);
    let two = Exemplar::from_rgb(
        "two colours",
        32,
        32,
        (0..32 * 32)
            .map(|i| if (i % 32) < 12 { a } else { b })
            .collect(),
    )
    .unwrap();
    let constant = vec![c; 16 * 16];
    let cpu_const = energy_cpu(&two, &constant, 16, 16, 1000).unwrap();
    assert_eq!(cpu_const, vec![245_000; 100]);
    let (_, analysis) = terra_crop();
    let (terra, _) = terra_crop();
    let params = SynthParams::new(analysis.levels.len() as u32, 3, &[2], &[0.5]).unwrap();
    let synthesized = synthesize_cpu(analysis, &params, window(0, 0, 24, 20))
        .unwrap()
        .colours(terra);
    let cpu_synth = energy_cpu(terra, &synthesized, 24, 20, 1000).unwrap();
    with_gpu(|gpu| {
        let kernel = EnergyKernel::new(gpu).unwrap();
        assert_eq!(
            kernel.minima(leather, &leather.rgb, 64, 64, 64).unwrap(),
            cpu
        );
        assert_eq!(
            kernel.minima(&two, &constant, 16, 16, 1000).unwrap(),
            cpu_const
        );
        assert_eq!(
            kernel.minima(terra, &synthesized, 24, 20, 1000).unwrap(),
            cpu_synth
        );
    });
    assert_eq!(histogram_distance(&leather.rgb, &leather.rgb), 0.0);
    assert_eq!(histogram_distance(&two.rgb, &constant), 1.0);
}

#[test]
fn bad_exemplars_are_rejected_with_the_file_and_limit() {
    let dir = tempfile::tempdir().unwrap();
    let small = dir.path().join("small.png");
    image::RgbImage::new(8, 40).save(&small).unwrap();
    let e = Exemplar::load(&small).unwrap_err();
    assert!(
        matches!(
            e,
            SynthError::Size {
                width: 8,
                height: 40,
                ..
            }
        ),
        "{e}"
    );
    let msg = e.to_string();
    assert!(
        msg.contains("small.png") && msg.contains(&MIN_EXEMPLAR_SIDE.to_string()),
        "{msg}"
    );

    let missing = dir.path().join("missing.png");
    assert!(matches!(
        Exemplar::load(&missing),
        Err(SynthError::Io { .. })
    ));

    let garbage = dir.path().join("garbage.png");
    std::fs::write(&garbage, b"not an image at all").unwrap();
    assert!(matches!(
        Exemplar::load(&garbage),
        Err(SynthError::Decode { .. })
    ));

    // A real pattern with its magic or channel count damaged.
    let good = std::fs::read(asset_exemplar("leather.pat")).unwrap();
    let mut bad_magic = good.clone();
    bad_magic[20..24].copy_from_slice(b"GIMP");
    let path = dir.path().join("magic.pat");
    std::fs::write(&path, &bad_magic).unwrap();
    let e = Exemplar::load(&path).unwrap_err();
    assert!(
        matches!(e, SynthError::PatternHeader { field: "magic", .. })
            && e.to_string().contains("magic.pat"),
        "{e}"
    );
    let mut five = good.clone();
    five[16..20].copy_from_slice(&5u32.to_be_bytes());
    let path = dir.path().join("five.pat");
    std::fs::write(&path, &five).unwrap();
    assert!(matches!(
        Exemplar::load(&path),
        Err(SynthError::Channels { channels: 5, .. })
    ));
    let path = dir.path().join("short.pat");
    std::fs::write(&path, &good[..good.len() - 10]).unwrap();
    let e = Exemplar::load(&path).unwrap_err();
    assert!(
        matches!(
            e,
            SynthError::PatternHeader {
                field: "pixels",
                ..
            }
        ),
        "{e}"
    );

    // Parameters out of range.
    let (_, analysis) = leather();
    assert!(SynthParams::new(7, 0, &[2], &[1.5]).is_err());
    assert!(SynthParams::new(7, 0, &[2], &[0.1, 0.2]).is_err());
    assert!(SynthParams::new(7, 0, &[2, 2], &[0.5]).is_err());
    assert!(SynthParams::new(7, 0, &[9], &[0.5]).is_err());
    let too_much = SynthParams::new(7, 0, &[2], &[0.5])
        .unwrap()
        .with_period_penalty(MAX_PERIOD_PENALTY + 1)
        .unwrap_err();
    assert!(
        too_much.to_string().contains("period penalty"),
        "{too_much}"
    );
    let params = SynthParams::new(analysis.levels.len() as u32, 0, &[2], &[0.5]).unwrap();
    assert!(synthesize_cpu(analysis, &params, window(0, 0, 0, 4)).is_err());
}
