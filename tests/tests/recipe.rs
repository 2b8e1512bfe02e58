//! The solid recipe: its exemplar preparation is the pieces' (fit, roles, feature channel,
//! orientation), its defaults are the synthesizer's, and the windowed and lazy synthesizers
//! built from one preparation give the volume the pieces give, voxel for voxel.

use lazysolid_synth::cache::{CacheOutcome, DiskCache};
use lazysolid_synth::feature::DEFAULT_FEATURE_WEIGHT;
use lazysolid_synth::solid::lazy::MemoryPolicy;
use lazysolid_synth::solid::{
    analyze_solid, candidates_key, default_solid_jitter, default_solid_passes, voxel_colour,
    CandidateBuilder, CandidateParams, GpuSolidSynthesizer, Orientation, SolidExemplars,
    SolidRecipe, SolidSchedule, VolumeBox, DEFAULT_SOLID_PARALLEL_LEVELS,
};
use lazysolid_synth::{load_solid, FitMode, SynthParams};
use lazysolid_tests::{exemplar_crop, with_gpu};
use std::path::{Path, PathBuf};

/// A `side`² crop at (`x0`, `y0`) of an asset pattern, written as a PNG into `dir`.
fn crop_file(dir: &Path, name: &str, x0: u32, y0: u32, side: u32) -> PathBuf {
    let e = exemplar_crop(name, x0, y0, side, side);
    let path = dir.join(format!(
        "{}-{x0}-{y0}-{side}.png",
        name.trim_end_matches(".pat")
    ));
    image::RgbImage::from_fn(side, side, |x, y| image::Rgb(e.at(x, y)))
        .save(&path)
        .unwrap();
    path
}

/// The exemplars as the pieces make them: what `SolidRecipe::load` must equal.
fn by_hand(path: &Path, orientation: Orientation) -> SolidExemplars {
    let image = load_solid(path, FitMode::Auto, None).unwrap().exemplar;
    SolidExemplars::new(image, [None, None, None])
        .unwrap()
        .with_feature_weight(DEFAULT_FEATURE_WEIGHT)
        .unwrap()
        .with_orientation(orientation)
        .0
}

fn same_exemplars(a: &SolidExemplars, b: &SolidExemplars) {
    assert_eq!(a.role_image, b.role_image);
    assert_eq!(a.feature_weight, b.feature_weight);
    assert_eq!(a.feature_mask, b.feature_mask);
    assert_eq!(a.images.len(), b.images.len());
    for (x, y) in a.images.iter().zip(&b.images) {
        assert_eq!((x.width, x.height), (y.width, y.height));
        assert_eq!(x.rgb, y.rgb);
    }
}

/// A recipe's defaults are the synthesizer's: passes, jitter, parallel levels, candidates,
/// builder, orientation, feature weight, seed.
#[test]
fn a_recipe_starts_from_the_synthesizer_defaults() {
    let recipe = SolidRecipe::new("any.png");
    assert_eq!(recipe.candidates, CandidateParams::default());
    assert_eq!(recipe.builder, CandidateBuilder::Auto);
    assert_eq!(recipe.orientation, Orientation::Auto);
    assert_eq!(recipe.feature_weight, DEFAULT_FEATURE_WEIGHT);
    assert_eq!(recipe.fit, FitMode::Auto);
    assert_eq!(recipe.schedule, SolidSchedule::default());
    assert!(!recipe.relief);
    for levels in [3, 5, 7] {
        let expected = SynthParams::new(
            levels,
            recipe.seed,
            &default_solid_passes(levels),
            &default_solid_jitter(levels),
        )
        .unwrap()
        .with_parallel_levels(DEFAULT_SOLID_PARALLEL_LEVELS.min(levels))
        .unwrap();
        assert_eq!(recipe.synth_params(levels).unwrap(), expected, "{levels}");
    }
    // A schedule that does not fit the pyramid is refused, naming what is wrong.
    let bad = SolidRecipe {
        schedule: SolidSchedule {
            passes: vec![1, 2],
            ..SolidSchedule::default()
        },
        ..recipe
    };
    let msg = bad.synth_params(5).unwrap_err().to_string();
    assert!(msg.contains("pass"), "{msg}");
}

/// The preparation is the pieces': the main image fitted, each role image fitted to its side,
/// the main image's fit dropped when all three roles are given, the orientation rule applied
/// (granite's veins lie on the diagonal the rule mirrors) and reported; a missing role image
/// is named.
#[test]
fn the_recipe_prepares_exemplars_as_the_pieces_do() {
    let dir = tempfile::tempdir().unwrap();
    let granite = lazysolid_tests::asset_exemplar("granite1.pat");
    let sources = SolidRecipe {
        exemplar_side: Some(32),
        ..SolidRecipe::new(&granite)
    }
    .load()
    .unwrap();
    let image = load_solid(&granite, FitMode::Auto, Some(32))
        .unwrap()
        .exemplar;
    let hand = SolidExemplars::new(image, [None, None, None]).unwrap();
    let (oriented, mirroring) = hand.clone().with_orientation(Orientation::Auto);
    assert!(mirroring.mirrored.is_some(), "{mirroring}");
    assert_eq!(sources.mirroring, mirroring);
    same_exemplars(&sources.exemplars, &oriented);
    same_exemplars(&sources.given, &hand);
    assert_eq!(sources.fits.len(), 1);

    // Roles: a 64² image beside a 32² main image is fitted to 32².
    let main = crop_file(dir.path(), "leather.pat", 0, 0, 32);
    let big = crop_file(dir.path(), "walnut.pat", 0, 0, 64);
    let sources = SolidRecipe {
        roles: [None, Some(big.clone()), None],
        ..SolidRecipe::new(&main)
    }
    .load()
    .unwrap();
    assert_eq!(sources.exemplars.side(), 32);
    assert_eq!(sources.fits.len(), 2);
    assert_eq!(sources.exemplars.role_image, [0, 1, 0]);
    let all = SolidRecipe {
        roles: [Some(big.clone()), Some(main.clone()), Some(big)],
        ..SolidRecipe::new(&main)
    }
    .load()
    .unwrap();
    assert_eq!(all.fits.len(), 3, "the unused main image's fit is dropped");
    assert_eq!(all.exemplars.side(), 32);
    let missing = SolidRecipe {
        roles: [None, None, Some(dir.path().join("nowhere.png"))],
        ..SolidRecipe::new(&main)
    }
    .load()
    .unwrap_err()
    .to_string();
    assert!(missing.contains("nowhere.png"), "{missing}");
    let weight = SolidRecipe {
        feature_weight: 100_000,
        ..SolidRecipe::new(&main)
    }
    .load()
    .unwrap_err()
    .to_string();
    assert!(weight.contains("--feature-weight"), "{weight}");
}

/// One preparation, two synthesizers: the recipe's windowed cube equals the volume the pieces
/// make (their own analysis, parameters and synthesizer) triple for triple, and the recipe's lazy
/// state returns the cube's colours at every requested voxel. The candidates go through a
/// cache: a second preparation reads them back.
#[test]
fn windowed_and_lazy_synthesizers_of_one_recipe_give_the_pieces_volume() {
    let dir = tempfile::tempdir().unwrap();
    let path = crop_file(dir.path(), "leather.pat", 8, 8, 16);
    let recipe = SolidRecipe {
        seed: 5,
        builder: CandidateBuilder::Host,
        ..SolidRecipe::new(&path)
    };
    let cache = DiskCache::new(dir.path().join("cache"));
    with_gpu(|gpu| {
        let sources = recipe.load().unwrap();
        let prepared = sources.prepare(gpu, Some(&cache), &mut |_, _| {}).unwrap();
        assert_eq!(prepared.cached, CacheOutcome::Miss);
        let again = sources.prepare(gpu, Some(&cache), &mut |_, _| {}).unwrap();
        assert_eq!(again.cached, CacheOutcome::Hit);
        assert!(
            again.candidates == prepared.candidates,
            "read back as written"
        );

        let exemplars = by_hand(&path, Orientation::Auto);
        same_exemplars(prepared.exemplars(), &exemplars);
        let analysis = analyze_solid(&exemplars);
        // The pieces' exemplars and parameters name the same cache entry: the same
        // candidates, without computing them twice.
        assert_eq!(
            candidates_key(&exemplars, &CandidateParams::default()),
            candidates_key(prepared.exemplars(), &recipe.candidates)
        );
        let candidates = &prepared.candidates;
        let levels = analysis.levels.len() as u32;
        let params = SynthParams::new(
            levels,
            5,
            &default_solid_passes(levels),
            &default_solid_jitter(levels),
        )
        .unwrap()
        .with_parallel_levels(DEFAULT_SOLID_PARALLEL_LEVELS.min(levels))
        .unwrap();
        let window = VolumeBox {
            origin: [-5, 3, 11],
            size: [16; 3],
        };
        let cube = prepared.cube(gpu, window, &mut |_| {}).unwrap();
        let (pieces, _) = GpuSolidSynthesizer::new(gpu, &analysis, candidates)
            .unwrap()
            .synthesize(&analysis, candidates, &params, window, false, &mut |_| {})
            .unwrap();
        assert!(cube.synthesis.window_triples() == pieces.window_triples());
        assert!(cube.colours == pieces.colours(&exemplars));

        // The lazy state at R = 32 over the same voxels (inside [0, 32)³): its colours are
        // the windowed synthesizer's.
        let inner = VolumeBox {
            origin: [0; 3],
            size: [16; 3],
        };
        let full = prepared.cube(gpu, inner, &mut |_| {}).unwrap();
        let mut state = prepared.lazy(gpu, 32, MemoryPolicy::Keep).unwrap();
        let voxels: Vec<[i32; 3]> = (0..inner.voxels())
            .step_by(7)
            .map(|i| inner.position(i))
            .collect();
        let (triples, _) = state.request(&voxels).unwrap();
        for (p, t) in voxels.iter().zip(&triples) {
            assert_eq!(
                voxel_colour(prepared.exemplars(), *t),
                full.colours[inner.index(*p)],
                "{p:?}"
            );
        }
    });
}
