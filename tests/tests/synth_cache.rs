//! The on-disk cache of exemplar analyses: a hit is bit-identical to a fresh analysis, any
//! change of pixels or parameters misses, and a damaged entry is recomputed (never trusted,
//! never a panic). Every test uses its own temporary cache folder.

use lazysolid_synth::feature::FeatureMask;
use lazysolid_synth::{
    analysis_key, analyze, analyze_cached, AnalysisParams, CacheOutcome, DiskCache, Exemplar,
    ExemplarAnalysis, ANALYSIS_CACHE_KIND,
};
use lazysolid_tests::exemplar_crop;
use std::path::PathBuf;
use std::sync::OnceLock;

/// A 32×40 crop of GIMP's terra pattern (small, so the analysis is quick) and its analysis.
fn terra_crop() -> &'static (Exemplar, ExemplarAnalysis) {
    static CELL: OnceLock<(Exemplar, ExemplarAnalysis)> = OnceLock::new();
    CELL.get_or_init(|| {
        let exemplar = exemplar_crop("terra.pat", 0, 0, 32, 40);
        let analysis = analyze(&exemplar, &AnalysisParams::default()).unwrap();
        (exemplar, analysis)
    })
}

/// The entry files in a cache folder (and nothing else may be there: no temporary files).
fn entries(cache: &DiskCache) -> Vec<PathBuf> {
    let folder = cache.dir().join(ANALYSIS_CACHE_KIND);
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    for f in &files {
        assert_eq!(f.extension().unwrap(), "bin", "stray file {}", f.display());
    }
    files
}

#[test]
fn a_hit_is_bit_identical_to_the_analysis() {
    let (exemplar, fresh) = terra_crop();
    let dir = tempfile::tempdir().unwrap();
    let cache = DiskCache::new(dir.path().join("cache"));
    let params = AnalysisParams::default();
    let (first, outcome) = analyze_cached(exemplar, &params, Some(&cache)).unwrap();
    assert_eq!(outcome, CacheOutcome::Miss);
    assert_eq!(&first, fresh);
    assert_eq!(entries(&cache).len(), 1);
    // A second cache object on the same folder stands for a later run of the program.
    let later = DiskCache::new(cache.dir());
    let (second, outcome) = analyze_cached(exemplar, &params, Some(&later)).unwrap();
    assert_eq!(outcome, CacheOutcome::Hit);
    assert_eq!(&second, fresh);
    // Bit-identical, floats included.
    for (a, b) in second.levels.iter().zip(&fresh.levels) {
        assert_eq!(a.residual_variance.to_bits(), b.residual_variance.to_bits());
    }
    let (_, outcome) = analyze_cached(exemplar, &params, None).unwrap();
    assert_eq!(outcome, CacheOutcome::Disabled);
}

#[test]
fn changed_parameters_or_pixels_miss() {
    let (exemplar, _) = terra_crop();
    let dir = tempfile::tempdir().unwrap();
    let cache = DiskCache::new(dir.path());
    let base = AnalysisParams::default();
    let mut changed_pixel = exemplar.clone();
    changed_pixel.rgb[617][1] ^= 1;
    let cases: [(&Exemplar, AnalysisParams); 7] = [
        (exemplar, base),
        (exemplar, AnalysisParams { spread: 8, ..base }),
        (exemplar, AnalysisParams { k: 3, ..base }),
        (
            exemplar,
            AnalysisParams {
                feature_weight: 0,
                ..base
            },
        ),
        (
            exemplar,
            AnalysisParams {
                feature_mask: FeatureMask::MinimumError,
                ..base
            },
        ),
        (
            exemplar,
            AnalysisParams {
                toroidal: false,
                ..base
            },
        ),
        (&changed_pixel, base),
    ];
    for (i, (e, p)) in cases.iter().enumerate() {
        let (analysis, outcome) = analyze_cached(e, p, Some(&cache)).unwrap();
        assert_eq!(outcome, CacheOutcome::Miss, "case {i}");
        assert_eq!(analysis, analyze(e, p).unwrap(), "case {i}");
        assert_eq!(entries(&cache).len(), i + 1, "case {i}");
    }
    // And each of them hits afterwards.
    for (i, (e, p)) in cases.iter().enumerate() {
        let (_, outcome) = analyze_cached(e, p, Some(&cache)).unwrap();
        assert_eq!(outcome, CacheOutcome::Hit, "case {i}");
    }
}

#[test]
fn damaged_entries_are_recomputed() {
    let (exemplar, fresh) = terra_crop();
    let dir = tempfile::tempdir().unwrap();
    let cache = DiskCache::new(dir.path());
    let params = AnalysisParams::default();
    analyze_cached(exemplar, &params, Some(&cache)).unwrap();
    let path = cache.entry_path(ANALYSIS_CACHE_KIND, &analysis_key(exemplar, &params));
    let good = std::fs::read(&path).unwrap();
    // Another exemplar's entry, copied over this key's file.
    let other = AnalysisParams {
        spread: 4,
        ..params
    };
    analyze_cached(exemplar, &other, Some(&cache)).unwrap();
    let foreign =
        std::fs::read(cache.entry_path(ANALYSIS_CACHE_KIND, &analysis_key(exemplar, &other)))
            .unwrap();
    let mut flipped = good.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 0x40;
    let mut header = good.clone();
    header[0] = b'X';
    let damages: [(&str, Vec<u8>, &str); 5] = [
        ("flipped payload bit", flipped, "checksum"),
        ("truncated", good[..good.len() / 2].to_vec(), "truncated"),
        ("empty", Vec::new(), "header"),
        ("bad magic", header, "magic"),
        ("another key's entry", foreign, "another key"),
    ];
    for (what, bytes, reason) in damages {
        std::fs::write(&path, bytes).unwrap();
        let (analysis, outcome) = analyze_cached(exemplar, &params, Some(&cache)).unwrap();
        match &outcome {
            CacheOutcome::Recomputed(r) => {
                assert!(r.contains(reason), "{what}: {r}");
                assert!(r.contains(&path.display().to_string()), "{what}: {r}");
            }
            o => panic!("{what}: {o:?}"),
        }
        assert!(outcome.warning().is_some());
        assert_eq!(&analysis, fresh, "{what}");
        // The entry was rewritten whole.
        assert_eq!(std::fs::read(&path).unwrap(), good, "{what}");
        let (_, outcome) = analyze_cached(exemplar, &params, Some(&cache)).unwrap();
        assert_eq!(outcome, CacheOutcome::Hit, "{what}");
    }
    // A whole entry whose payload is not an analysis (a consumer's format changed without a
    // version bump, say): refused by the decoder, recomputed.
    let key = analysis_key(exemplar, &params);
    cache
        .store(ANALYSIS_CACHE_KIND, &key, b"not an analysis")
        .unwrap();
    let (analysis, outcome) = analyze_cached(exemplar, &params, Some(&cache)).unwrap();
    assert!(
        matches!(&outcome, CacheOutcome::Recomputed(r) if r.contains("does not decode")),
        "{outcome:?}"
    );
    assert_eq!(&analysis, fresh);
    assert_eq!(entries(&cache).len(), 2);
}

#[test]
fn an_unwritable_cache_only_costs_the_analysis() {
    let (exemplar, fresh) = terra_crop();
    let dir = tempfile::tempdir().unwrap();
    // The cache folder is a file: nothing can be stored under it.
    let blocker = dir.path().join("not-a-folder");
    std::fs::write(&blocker, b"").unwrap();
    let cache = DiskCache::new(&blocker);
    let (analysis, outcome) =
        analyze_cached(exemplar, &AnalysisParams::default(), Some(&cache)).unwrap();
    assert_eq!(&analysis, fresh);
    match outcome {
        CacheOutcome::NotStored(reason) => assert!(reason.contains("not-a-folder"), "{reason}"),
        o => panic!("{o:?}"),
    }
}
