//! `lazysolid bench solid`: solid synthesis times, peak memory, the quality table with and without
//! the ablations, and the figures.

use crate::support::{fnv1a, lazysolid, run, BenchRun};

/// The smallest case: 16² exemplars, a 16³ cube, one pass, one run.
const SMALLEST: [&str; 14] = [
    "--candidate-sides",
    "16",
    "--side",
    "16",
    "--voxel-res",
    "16",
    "--passes",
    "1",
    "--energy-samples",
    "64",
    "--runs",
    "1",
    "--warmup",
    "0",
];

/// `bench solid` end to end at the smallest size: the candidate row, the synthesis row, the
/// cold and warm end-to-end rows (each checks what the candidate cache did), the peak memory,
/// the quality table with its variants and the figures.
#[test]
fn bench_solid_writes_times_quality_and_figures() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "solid",
                "--quick",
                // Veins on the negative diagonal: the orientation rule mirrors E_y, so the
                // "as given" ablation runs too.
                "--exemplars",
                "granite1",
                "--three",
                "",
                "--solid-seeds",
                "2",
            ])
            .args(SMALLEST),
        out.path(),
        &[
            "granite1 16² candidates",
            "lazysolid gpu kernels (wall)",
            "lazysolid host, pruned (wall)",
            "lazysolid gpu synthesis (wall)",
            "lazysolid end-to-end cold (wall)",
            "lazysolid end-to-end warm (wall)",
            "granite1 16³ peak GPU MiB",
            "own role",
            "mean colour",
            "keep current",
            "crossbar only",
            "no balance",
            "balance finest",
            "no feature",
            "otsu mask",
            "as given",
            "extruded E_z",
            "2d synth",
            // The 100² pattern fitted to the 16² measured (--fit auto).
            "granite1: exemplar fit: granite1.pat 100x100 grey → Lanczos3 resample 16x16",
            "granite1: orientation: diagonal correlation -0.307 / -0.307 / -0.307: E_y mirrored left-right",
        ],
    );
    let implementations = bench.column("implementation");
    assert_eq!(implementations.len(), 5, "{implementations:?}");
    let figures = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(figures.join("quality.json")).unwrap())
            .unwrap();
    assert_eq!(
        json[0]["exemplars"][0],
        "granite1.pat 100x100 grey → Lanczos3 resample 16x16"
    );
    let quality = std::fs::read_to_string(figures.join("quality.csv")).unwrap();
    // Thirteen variants, three axes each, plus the header.
    assert_eq!(quality.lines().count(), 1 + 13 * 3, "{quality}");
    assert!(
        quality
            .lines()
            .next()
            .unwrap()
            .contains(",anisotropy,exemplar_anisotropy,diagonal,exemplar_diagonal,"),
        "{quality}"
    );
    let header = quality.lines().next().unwrap();
    assert!(
        header.contains(",slices_swd_band_fine,slices_swd_band_mid,slices_swd_band_coarse,slices_band_contrast_fine,slices_band_contrast_mid,slices_band_contrast_coarse,"),
        "{header}"
    );
    let fields = header.split(',').count();
    for line in quality.lines() {
        assert_eq!(line.split(',').count(), fields, "{line}");
    }
    assert!(figures.join("quality.json").exists());
    // Every figure byte for byte what the suite drew before the solid recipe replaced the
    // command line's pipeline (10d48bd); a deliberate change of the synthesis updates them.
    // (At 16² the feature channel finds nothing in granite1: the default's slices are the
    // `no feature` ablation's.)
    for (name, digest) in [
        ("granite1-16-slices.png", 0xff5f_e1f7_aaec_b3f6_u64),
        ("granite1-16-as-given-slices.png", 0x9c14_e257_7bb0_6995),
        ("granite1-16-keep-current-slices.png", 0xffb5_e10b_8e62_2c7a),
        ("granite1-16-no-balance-slices.png", 0x061c_887b_03fb_6775),
        ("granite1-16-no-feature-slices.png", 0xff5f_e1f7_aaec_b3f6),
        (
            "granite1-16-ordered-finest-slices.png",
            0x4f94_25c0_1ac8_4a93,
        ),
        ("granite1-slab.png", 0xe4ff_75a9_0fe2_e39b),
    ] {
        let bytes = std::fs::read(figures.join(name)).unwrap();
        assert_eq!(fnv1a(&bytes), digest, "{name}");
    }
    assert!(bench.stdout.contains("quality table"), "{}", bench.stdout);
    without_ablations_scores_the_default_only(&quality);
}

/// `bench solid --no-ablations` on the same exemplar with one seed (the host's candidates,
/// which equal the kernels'): the default synthesis, the colour rules, the extruded reference
/// and the 2D synthesis are scored; none of the ablation volumes is made. Against `pooled`, the
/// quality table of the run above with `--solid-seeds 2`: the `solid` row's eight-slice
/// figures pool a second seed's slices while its mid-slice figures and the other rows stay the
/// first seed's. (One test with the run above: each run precomputes its own candidates.)
fn without_ablations_scores_the_default_only(pooled: &str) {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "solid",
                "--quick",
                "--no-ablations",
                "--exemplars",
                "granite1",
            ])
            .args(["--three", "", "--candidates", "host", "--solid-seeds", "1"])
            .args(SMALLEST),
        out.path(),
        &["own role", "mean colour", "extruded E_z", "2d synth"],
    );
    let figures = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder")
        .clone();
    let quality = std::fs::read_to_string(figures.join("quality.csv")).unwrap();
    let slices = figures.join("granite1-16-slices.png").exists();
    let ablation = figures.join("granite1-16-keep-current-slices.png").exists();
    let stdout = bench.stdout;
    for absent in [
        "keep current",
        "crossbar only",
        "no balance",
        "balance finest",
        "no feature",
    ] {
        assert!(!stdout.contains(absent), "{absent}:\n{stdout}");
    }
    // Five variants, three axes each, plus the header.
    assert_eq!(quality.lines().count(), 1 + 5 * 3, "{quality}");
    assert!(slices);
    assert!(!ablation);

    let column = |csv: &str, name: &str| -> Vec<(String, String)> {
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let at = header.iter().position(|h| *h == name).unwrap();
        csv.lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[1].to_string(), f[at].to_string())
            })
            .collect()
    };
    let solid = |csv: &str, name: &str| -> Vec<String> {
        column(csv, name)
            .into_iter()
            .filter(|(variant, _)| variant == "solid")
            .map(|(_, v)| v)
            .collect()
    };
    // (At 16² the SWD has too few patches and reads NaN; the blockiness and band contrast
    // are figures there.)
    assert_eq!(solid(&quality, "blockiness"), solid(pooled, "blockiness"));
    assert_ne!(
        solid(&quality, "slices_blockiness"),
        solid(pooled, "slices_blockiness"),
        "{pooled}"
    );
    assert_ne!(
        solid(&quality, "slices_band_contrast_fine"),
        solid(pooled, "slices_band_contrast_fine"),
        "{pooled}"
    );
    // The other rows of this run, against the same rows of the pooled one (which also has
    // the ablations' rows).
    let others = |csv: &str| -> Vec<(String, String)> {
        column(csv, "slices_blockiness")
            .into_iter()
            .filter(|(variant, _)| {
                ["own role", "mean colour", "extruded E_z", "2d synth"].contains(&variant.as_str())
            })
            .collect()
    };
    assert_eq!(others(&quality).len(), 4 * 3, "{quality}");
    assert_eq!(others(&quality), others(pooled));
}

#[test]
fn bench_solid_refuses_a_seed_count_out_of_range() {
    for bad in ["0", "9"] {
        let (ok, _, err) = run(lazysolid().args(["bench", "solid", "--solid-seeds", bad]));
        assert!(
            !ok && err.contains("--solid-seeds") && err.contains("1..=8"),
            "{err}"
        );
    }
}

#[test]
fn bench_solid_refuses_auto_candidates() {
    let (ok, _, err) = run(lazysolid().args(["bench", "solid", "--candidates", "auto,host"]));
    assert!(
        !ok && err.contains("--candidates auto") && err.contains("host, gpu"),
        "{err}"
    );
}
