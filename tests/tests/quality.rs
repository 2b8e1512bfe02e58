//! The quality figures of synthesis (`synth::quality`) on constructed cases built from real
//! exemplars: a shifted copy, a blockified copy, a blur and an unrelated material must rank
//! as a person would rank them.

use lazysolid_synth::quality::{
    band_contrast, band_deviations, Blockiness, LinearImage, SwdCalibration, SwdParams,
};
use lazysolid_synth::Exemplar;
use lazysolid_tests::asset_exemplar;

fn load(name: &str) -> LinearImage {
    let e = Exemplar::load(&asset_exemplar(name)).unwrap_or_else(|e| panic!("{e}"));
    LinearImage::from_rgb8(&e.rgb, e.width as usize, e.height as usize)
}

/// The exemplar moved by (dx, dy) on its torus: the same patches but at its seams.
fn shifted(im: &LinearImage, dx: usize, dy: usize) -> LinearImage {
    let (w, h) = (im.width, im.height);
    LinearImage {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| im.at((i % w + dx) % w, (i / w + dy) % h))
            .collect(),
    }
}

/// Every `b`×`b` block takes the colour of its top-left pixel.
fn blockified(im: &LinearImage, b: usize) -> LinearImage {
    let w = im.width;
    LinearImage {
        pixels: (0..im.pixels.len())
            .map(|i| im.at((i % w) / b * b, (i / w) / b * b))
            .collect(),
        ..im.clone()
    }
}

/// Two passes of a 3×3 box blur (edges clamped).
fn blurred(im: &LinearImage) -> LinearImage {
    let mut out = im.clone();
    for _ in 0..2 {
        let src = out.clone();
        let (w, h) = (src.width, src.height);
        for y in 0..h {
            for x in 0..w {
                let mut acc = [0.0f32; 3];
                for dy in -1isize..=1 {
                    for dx in -1isize..=1 {
                        let xx = (x as isize + dx).clamp(0, w as isize - 1) as usize;
                        let yy = (y as isize + dy).clamp(0, h as isize - 1) as usize;
                        let p = src.at(xx, yy);
                        (0..3).for_each(|c| acc[c] += p[c] / 9.0);
                    }
                }
                out.pixels[y * w + x] = acc;
            }
        }
    }
    out
}

/// The top-left `w`×`h` of another material, tiled when it is smaller.
fn unrelated(other: &LinearImage, w: usize, h: usize) -> LinearImage {
    LinearImage {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| other.at((i % w) % other.width, (i / w) % other.height))
            .collect(),
    }
}

#[test]
fn figures_rank_constructed_cases_as_a_person_would() {
    for (name, other) in [
        ("walnut.pat", "pink_marble.pat"),
        ("pink_marble.pat", "crinklepaper.pat"),
        ("crinklepaper.pat", "walnut.pat"),
        ("brick.pat", "terra.pat"),
    ] {
        let ex = load(name);
        let cal = SwdCalibration::new(&ex, SwdParams::default());
        let cases = [
            ("shifted", shifted(&ex, ex.width / 3, ex.height / 3)),
            (
                "blocks",
                blockified(&shifted(&ex, ex.width / 3, ex.height / 3), 6),
            ),
            ("blur", blurred(&ex)),
            ("unrelated", unrelated(&load(other), ex.width, ex.height)),
        ];
        let scores: Vec<(f64, f64)> = cases
            .iter()
            .map(|(case, im)| {
                let (s, b) = (cal.measure(im), Blockiness::measure(im, &ex));
                println!(
                    "{name} {case}: SWD {:.3} per band {:?}, ratio {:.2} (unit {:?}, patches {:?}); blockiness {:.2} (axis share {:.3}, exemplar {:.3})",
                    s.mean, s.per_octave, s.ratio, cal.unit, cal.counts, b.ratio, b.share, b.exemplar_share
                );
                (s.ratio, b.ratio)
            })
            .collect();
        let [shifted, blocks, blur, unrelated] = [0, 1, 2, 3].map(|i| scores[i]);
        // Measured on 2026-12-03 (SWD ratio; blockiness): shifted 0.51-0.78; 1.01-1.05,
        // blocks 0.92-2.29; 1.48-3.41, blur 2.38-6.23; 0.92-1.11, unrelated 2.46-22.3.
        // A shifted copy is as close as the exemplar's two halves are to each other, or closer.
        assert!(shifted.0 < 1.0, "{name}: shifted copy {shifted:?}");
        assert!(
            (0.9..1.1).contains(&shifted.1),
            "{name}: shifted copy {shifted:?}"
        );
        // Blocks are flagged by the blockiness and are further than the copy they came from.
        assert!(blocks.1 > 1.4, "{name}: blocks {blocks:?}");
        assert!(
            blocks.0 > shifted.0,
            "{name}: blocks {blocks:?} vs {shifted:?}"
        );
        // A blur is not blocky, but its lost detail makes it far from the material.
        assert!((0.85..1.15).contains(&blur.1), "{name}: blur {blur:?}");
        assert!(blur.0 > 2.0, "{name}: blur {blur:?}");
        // Another material is furthest from both the copy and the blocks.
        assert!(unrelated.0 > 2.0, "{name}: unrelated {unrelated:?}");
        assert!(
            unrelated.0 > shifted.0.max(blocks.0),
            "{name}: unrelated {unrelated:?}"
        );
    }
}

/// The SWD's bands say at which scale an image departs from the material: a blur loses the
/// finest detail, so its finest band is the furthest; the ratio is the bands' mean.
#[test]
fn the_bands_place_a_blur_in_the_finest_detail() {
    for name in [
        "walnut.pat",
        "pink_marble.pat",
        "crinklepaper.pat",
        "brick.pat",
    ] {
        let ex = load(name);
        let cal = SwdCalibration::new(&ex, SwdParams::default());
        let report = cal.measure(&blurred(&ex));
        let bands = report.bands();
        println!("{name} blur: bands fine → coarse {bands:?}");
        assert_eq!(report.band_ratios.len(), cal.octaves());
        let mean = report.band_ratios.iter().sum::<f64>() / report.band_ratios.len() as f64;
        assert!((mean - report.ratio).abs() < 1e-12, "{report:?}");
        assert!(
            bands[1..].iter().all(|&b| b.is_nan() || b < bands[0]),
            "{name}: a blur must be furthest in the finest band, {bands:?}"
        );
        // The band contrast gives the direction: the blur is smoother, a shifted copy is the
        // material's own contrast at every scale.
        let own = band_deviations(&ex);
        let blur = band_contrast(&blurred(&ex), &own);
        let copy = band_contrast(&shifted(&ex, ex.width / 3, ex.height / 3), &own);
        println!("{name}: band contrast blur {blur:?}, shifted copy {copy:?}");
        assert!(blur[0] < 0.6, "{name}: blur {blur:?}");
        assert!(
            copy.iter().all(|c| (0.9..1.1).contains(c)),
            "{name}: shifted copy {copy:?}"
        );
    }
}

#[test]
fn figures_are_deterministic_and_a_copy_scores_below_the_unit() {
    let ex = load("terra.pat");
    let cal = SwdCalibration::new(&ex, SwdParams::default());
    let (a, b) = (cal.measure(&ex), cal.measure(&ex));
    assert_eq!(a.per_octave, b.per_octave);
    // The exemplar against itself: only the sampling differs (the patches drawn for the
    // image and for the exemplar are different samples of one set).
    assert!(a.ratio < 0.8, "{a:?}");
    assert_eq!(cal.octaves(), cal.counts.len());
    // terra is 64²: its halves are too small for a third band of 64 patches.
    assert_eq!(cal.octaves(), 2, "{:?}", cal.counts);
    // A 16² exemplar's halves (8×16) hold 20 patches: no band, no figure.
    let tiny = ex.crop(0, 0, 16, 16);
    let none = SwdCalibration::new(&tiny, SwdParams::default());
    assert_eq!(none.octaves(), 0);
    assert!(none.measure(&tiny).ratio.is_nan());
    let s = Blockiness::measure(&ex, &ex);
    assert!((s.ratio - 1.0).abs() < 1e-12);
}
