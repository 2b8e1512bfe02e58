//! The `lazysolid` binary as a user runs it, including the ways it must fail clearly.

use std::process::Command;

fn lazysolid() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_lazysolid"));
    c.env_remove("LAZYSOLID_DEVICE")
        .env_remove("LAZYSOLID_VALIDATION");
    c
}

/// A path in the repository (scenes, assets).
fn repo(path: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(path)
}

fn run(c: &mut Command) -> (bool, String, String) {
    let out = c.output().expect("lazysolid runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// What a `lazysolid bench …` run left behind: its standard output and the entries of its
/// `--out` folder (the CSV, the JSON and the figures folder).
struct BenchRun {
    stdout: String,
    entries: Vec<std::path::PathBuf>,
}

impl BenchRun {
    /// Runs `c` with `--out-dir out` and the validation layer on; it must succeed and print
    /// every one of `needles`.
    fn new(c: &mut Command, out: &std::path::Path, needles: &[&str]) -> BenchRun {
        let (ok, stdout, err) = run(c.arg("--out-dir").arg(out).env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        for needle in needles {
            assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
        }
        let entries = std::fs::read_dir(out)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        BenchRun { stdout, entries }
    }

    /// The one entry with extension `ext`.
    fn file(&self, ext: &str) -> &std::path::Path {
        self.entries
            .iter()
            .find(|p| p.extension().is_some_and(|e| e == ext))
            .unwrap_or_else(|| panic!("no .{ext} file in {:?}", self.entries))
    }

    /// The JSON file, parsed.
    fn json(&self) -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(self.file("json")).unwrap()).unwrap()
    }

    /// The CSV file: its header and its records, each checked to have the header's length
    /// (fields holding commas are quoted).
    fn csv(&self) -> (csv::StringRecord, Vec<csv::StringRecord>) {
        let mut reader = csv::Reader::from_path(self.file("csv")).unwrap();
        let header = reader.headers().unwrap().clone();
        let records: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
        for r in &records {
            assert_eq!(r.len(), header.len(), "{r:?} against {header:?}");
        }
        (header, records)
    }

    /// The values of column `name` in every record.
    fn column(&self, name: &str) -> Vec<String> {
        let (header, records) = self.csv();
        let i = header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"));
        records.iter().map(|r| r[i].to_string()).collect()
    }

    /// The figures folder.
    fn figures(&self) -> &std::path::Path {
        self.entries
            .iter()
            .find(|p| p.is_dir())
            .expect("a figures folder")
    }

    /// The file names in the figures folder.
    fn figure_names(&self) -> Vec<String> {
        std::fs::read_dir(self.figures())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect()
    }
}

#[test]
fn device_lists_limits_and_marks_the_chosen_device() {
    let (ok, out, err) = run(lazysolid().arg("device"));
    assert!(ok, "{err}");
    for needle in [
        "maxStorageBufferRange",
        "device heap",
        "subgroup size",
        "shaderBufferInt64Atomics",
        "timestamp queries on a compute queue",
        "<- used by lazysolid",
    ] {
        assert!(out.contains(needle), "missing {needle:?} in:\n{out}");
    }
}

#[test]
fn the_memory_switch_is_reported_and_an_unknown_value_is_an_error() {
    let (ok, out, err) = run(lazysolid()
        .arg("device")
        .env("LAZYSOLID_MEMORY", "device-local"));
    assert!(ok, "{err}");
    assert!(out.contains("memory mode: device-local"), "{out}");
    assert!(out.contains("timestamp valid bits"), "{out}");
    let (ok, _, err) = run(lazysolid()
        .arg("device")
        .env("LAZYSOLID_MEMORY", "discrete"));
    assert!(!ok);
    assert!(
        err.contains("LAZYSOLID_MEMORY")
            && err.contains("discrete")
            && err.contains("device-local"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn no_vulkan_device_is_a_clear_error() {
    let (ok, _, err) = run(lazysolid()
        .arg("device")
        .env("VK_ICD_FILENAMES", "/nonexistent/icd.json")
        .env("VK_DRIVER_FILES", "/nonexistent/icd.json"));
    assert!(!ok);
    assert!(
        err.contains("no Vulkan device found") && err.contains("mesa-vulkan-drivers"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn missing_validation_layer_is_a_clear_error() {
    let empty = tempfile::tempdir().unwrap();
    let (ok, _, err) = run(lazysolid()
        .args(["bench", "prims", "--quick", "--runs", "1", "--warmup", "0"])
        .env("LAZYSOLID_VALIDATION", "1")
        .env("VK_LAYER_PATH", empty.path())
        .env("VK_ADD_LAYER_PATH", empty.path()));
    assert!(!ok);
    assert!(
        err.contains("VK_LAYER_KHRONOS_validation is not installed")
            && err.contains("vulkan-validationlayers"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    // --validation asks for the layer as LAZYSOLID_VALIDATION=1 does.
    let (ok, _, err) = run(lazysolid()
        .args(["--validation", "bench", "prims", "--quick"])
        .env("VK_LAYER_PATH", empty.path())
        .env("VK_ADD_LAYER_PATH", empty.path()));
    assert!(
        !ok && err.contains("VK_LAYER_KHRONOS_validation is not installed")
            && err.contains("--validation is given"),
        "{err}"
    );
}

#[test]
fn unknown_device_lists_the_available_ones() {
    let (ok, _, err) =
        run(lazysolid().args(["--device", "no-such-gpu", "bench", "prims", "--quick"]));
    assert!(!ok);
    assert!(
        err.contains("no-such-gpu") && err.contains("available devices: 0: "),
        "{err}"
    );
}

#[test]
fn bench_prims_writes_its_table_and_files() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid().args([
            "bench",
            "prims",
            "--scan-elements",
            "20000",
            "--sort-elements",
            "5000",
            "--runs",
            "2",
            "--warmup",
            "1",
        ]),
        out.path(),
        &[],
    );
    let stdout = &bench.stdout;
    assert!(
        stdout.contains("sort u32 keys") && stdout.contains("ratio"),
        "{stdout}"
    );
    let files = &bench.entries;
    assert_eq!(files.len(), 2, "no partial files left: {files:?}");
    let (header, records) = bench.csv();
    for column in [
        "suite", "date_utc", "revision", "device", "case", "builder", "ratio",
    ] {
        assert!(header.iter().any(|h| h == column), "{column}: {header:?}");
    }
    assert_eq!(records.len(), 14);
    let json = bench.json();
    assert!(json["run"]["driver"]
        .as_str()
        .is_some_and(|d| !d.is_empty()));
    // One timestamp for the run: in the JSON, every CSV row and both file names.
    let date = json["run"]["date_utc"].as_str().unwrap().to_string();
    assert!(
        bench.column("date_utc").iter().all(|d| *d == date),
        "{date}"
    );
    let stamp: String = date.chars().filter(char::is_ascii_digit).collect();
    let (day, time) = stamp.split_at(8);
    for ext in ["csv", "json"] {
        let name = bench
            .file(ext)
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        assert_eq!(name, format!("bench-prims-{day}-{time}.{ext}"));
    }
    assert_eq!(json["rows"].as_array().unwrap().len(), 14);
    assert!(
        json["rows"][0]["stats"]["samples_ms"]
            .as_array()
            .unwrap()
            .len()
            == 2
    );
}

#[test]
fn bad_arguments_are_refused() {
    let (ok, _, err) = run(lazysolid().args(["bench", "prims", "--runs", "0"]));
    assert!(!ok && err.contains("--runs must be at least 1"), "{err}");
    let (ok, _, err) = run(lazysolid().args(["bench", "prims", "--scan-elements", "lots"]));
    assert!(!ok && err.contains("invalid value"), "{err}");
}

#[test]
fn bench_hash_writes_tables_files_and_figures() {
    let mesh = repo("assets/meshes/armadillo.off");
    assert!(
        mesh.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        mesh.display()
    );
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "hash",
                "--image-res",
                "256x256",
                "--voxel-res",
                "32",
                "--random-keys",
                "4096",
                "--random-universe",
                "512",
            ])
            .args([
                "--load-factors",
                "0.5,0.85,0.99",
                "--runs",
                "1",
                "--warmup",
                "0",
                "--mesh",
            ])
            .arg(&mesh),
        out.path(),
        &[
            "image lf 0.85 query sorted 100%",
            "dense array (gpu)",
            "hashbrown (cpu, 2 threads)",
            "target: image lf 0.85 sorted queries coherent / random",
        ],
    );
    // A name with commas ("hashbrown (cpu, 2 threads)") is one quoted field: every record has
    // the header's length (checked by csv()) and the name reads back whole.
    let implementations = bench.column("implementation");
    assert!(
        implementations
            .iter()
            .any(|i| i == "hashbrown (cpu, 2 threads)"),
        "{implementations:?}"
    );
    assert!(bench
        .column("ratio")
        .iter()
        .any(|r| r.parse::<f64>().is_ok()));
    bench.file("json");
    let names = bench.figure_names();
    for f in [
        "age-histogram.png",
        "image-insert-vs-load-factor.png",
        "voxels-query-vs-load-factor.png",
        "table-contents-coherent-lf0.99.png",
        "max-age-map-random-lf0.85.png",
    ] {
        assert!(names.iter().any(|n| n == f), "missing {f} in {names:?}");
    }
    assert!(!names.iter().any(|n| n.contains("partial")), "{names:?}");
}

#[test]
fn bench_hash_refuses_bad_load_factors_and_missing_meshes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--load-factors", "0.5,1.5"]));
    assert!(
        !ok && err.contains("--load-factors must lie in (0, 1]"),
        "{err}"
    );
    let (ok, _, err) =
        run(lazysolid().args(["bench", "hash", "--quick", "--mesh", "/no/such/mesh.off"]));
    assert!(
        !ok && err.contains("/no/such/mesh.off") && err.contains("fetch-assets"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--datasets", "image,fish"]));
    assert!(
        !ok && err.contains("'fish'")
            && err.contains("--datasets")
            && err.contains("[possible values: random-2d, image, voxels]"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--schemes", "linear"]));
    assert!(
        !ok && err.contains("'linear'")
            && err.contains("[possible values: coherent, random, cuckoo]"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "hash", "--image-res", "256x128"]));
    assert!(
        !ok && err.contains("--image-res 256x128") && err.contains("square"),
        "{err}"
    );
}

/// Two 40x30 PNGs in a fresh folder: a gradient, and the same with a few pixels changed.
fn diff_pair() -> (tempfile::TempDir, std::path::PathBuf, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let reference = image::RgbImage::from_fn(40, 30, |x, y| {
        image::Rgb([(x * 6) as u8, (y * 8) as u8, ((x + y) * 3) as u8])
    });
    let mut test = reference.clone();
    for (x, y) in [(3, 4), (20, 15), (35, 27)] {
        test.put_pixel(x, y, image::Rgb([255, 255, 255]));
    }
    let (r, t) = (dir.path().join("ref.png"), dir.path().join("test.png"));
    reference.save(&r).unwrap();
    test.save(&t).unwrap();
    (dir, r, t)
}

/// The value printed on the `FLIP <name>` line.
fn flip_stat(stdout: &str, name: &str) -> f32 {
    stdout
        .lines()
        .find_map(|l| l.strip_prefix("FLIP ")?.strip_prefix(name))
        .unwrap_or_else(|| panic!("no FLIP {name} line in:\n{stdout}"))
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn diff_prints_statistics_and_writes_the_error_map() {
    let (dir, r, t) = diff_pair();
    let map = dir.path().join("error.png");
    let (ok, out, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .arg("--error-map")
        .arg(&map));
    assert!(ok, "{err}");
    assert!(out.contains("size        40x30 (1200 pixels)"), "{out}");
    let stats: Vec<f32> = ["mean", "median", "p95", "p99", "max"]
        .iter()
        .map(|n| flip_stat(&out, n))
        .collect();
    assert!(stats[0] > 0.0 && stats[0] < 0.05, "{out}");
    assert!(stats[1..].windows(2).all(|w| w[0] <= w[1]), "{out}");
    assert!(stats[4] > 0.3, "{out}");
    let written = image::open(&map).unwrap();
    assert_eq!((written.width(), written.height()), (40, 30));
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);

    // The same image against itself: zero everywhere.
    let (ok, out, err) = run(lazysolid().arg("diff").arg(&r).arg(&r));
    assert!(ok, "{err}");
    assert_eq!(flip_stat(&out, "mean"), 0.0);
    assert_eq!(flip_stat(&out, "max"), 0.0);
}

#[test]
fn diff_max_mean_sets_the_exit_status() {
    let (_dir, r, t) = diff_pair();
    let (ok, out, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "0.5"]));
    assert!(ok, "{err}");
    assert!(out.contains("is within --max-mean 0.5"), "{out}");

    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "0.0001"])
        .output()
        .unwrap();
    // Its own status: 3, apart from errors (1) and validation errors (2).
    assert_eq!(out.status.code(), Some(3));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("is above --max-mean 0.0001") && err.contains("test.png"),
        "{err}"
    );
    // The statistics are still printed before the verdict.
    assert!(String::from_utf8_lossy(&out.stdout).contains("FLIP mean"));

    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&t)
        .args(["--max-mean", "-1"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("outside 0..1"), "{err}");
    assert_eq!(out.status.code(), Some(1), "a bad argument is an error");
    // A missing image is an error too, not a failed comparison.
    let out = lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(r.with_file_name("nowhere.png"))
        .args(["--max-mean", "0.5"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    // `--help` documents the statuses.
    let (ok, help, _) = run(lazysolid().arg("--help"));
    assert!(ok && help.contains("Exit status:") && help.contains("3 `diff --max-mean`"));
}

#[test]
fn diff_bad_paths_are_named() {
    let (dir, r, _t) = diff_pair();
    let missing = dir.path().join("nowhere.png");
    let (ok, out, err) = run(lazysolid().arg("diff").arg(&r).arg(&missing));
    assert!(!ok && out.is_empty());
    assert!(
        err.contains("nowhere.png") && err.contains("cannot open") && !err.contains("panicked"),
        "{err}"
    );

    let small = dir.path().join("small.png");
    image::RgbImage::new(20, 30).save(&small).unwrap();
    let (ok, _, err) = run(lazysolid().arg("diff").arg(&r).arg(&small));
    assert!(
        !ok && err.contains("40x30") && err.contains("20x30") && err.contains("small.png"),
        "{err}"
    );

    let map = dir.path().join("missing-folder").join("map.png");
    let (ok, _, err) = run(lazysolid()
        .arg("diff")
        .arg(&r)
        .arg(&r)
        .arg("--error-map")
        .arg(&map));
    assert!(
        !ok && err.contains("error map") && err.contains("missing-folder"),
        "{err}"
    );
}

#[test]
fn render_writes_png_and_exr_and_says_where() {
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("interior.png");
    let (ok, stdout, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/interior.toml"))
        .arg("-o")
        .arg(&png)
        .args(["--spp", "2", "--res", "40x30"])
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    assert!(stdout.contains(&png.display().to_string()), "{stdout}");
    assert!(err.contains("Mrays/s"), "{err}");
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (40, 30));
    assert!(out.path().join("interior.exr").exists());
}

#[test]
fn render_refuses_bad_scenes_and_arguments() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\nfov_y = 40\n\n[render]\nwidth = 8\nheight = 8\nspp = 1\nfocus = 2\n",
    )
    .unwrap();
    let png = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("render").arg(&scene).arg("-o").arg(&png));
    assert!(!ok);
    assert!(
        err.contains("bad.toml:10") && err.contains("focus"),
        "the unknown key is named with its line: {err}"
    );
    assert!(!png.exists(), "no image is written for a bad scene");
    let (ok, _, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/interior.toml"))
        .arg("-o")
        .arg(&png)
        .args(["--res", "40by30"]));
    assert!(
        !ok && err.contains("WxH") && err.contains("40by30"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid()
        .arg("render")
        .arg(dir.path().join("missing.toml"))
        .arg("-o")
        .arg(&png));
    assert!(!ok && err.contains("missing.toml"), "{err}");
}

#[test]
fn synth_writes_texture_and_coordinate_map_with_metrics() {
    let exemplar = repo("assets/exemplars/terra.pat");
    assert!(
        exemplar.exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        exemplar.display()
    );
    let dir = tempfile::tempdir().unwrap();
    let cache = tempfile::tempdir().unwrap();
    let out = dir.path().join("terra.png");
    // The exemplar by its asset name, from a folder outside the repository.
    let synth = |extra: &[&str]| {
        let (ok, stdout, err) = run(lazysolid()
            .current_dir(dir.path())
            .arg("synth")
            .arg("terra")
            .args(["--res", "48x32", "--offset", "-70,5", "--seed", "4"])
            .args(["--energy-samples", "64"])
            .args(extra)
            .args(["-o", "terra.png"])
            .env("LAZYSOLID_CACHE_DIR", cache.path())
            .env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        assert!(stdout.contains("terra.pat"), "{stdout}");
        (stdout, std::fs::read(&out).unwrap())
    };
    // The first run analyses the exemplar and caches the analysis, the second reads it, and
    // both write the same image; --no-cache neither reads nor writes the cache.
    let (stdout, first) = synth(&[]);
    for needle in [
        "cache miss",
        "synthesis (GPU)",
        "neighbourhood energy",
        "colour histogram distance",
    ] {
        assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
    }
    let cached: Vec<_> = std::fs::read_dir(cache.path().join("synth-analysis"))
        .unwrap()
        .collect();
    assert_eq!(cached.len(), 1);
    let (stdout, second) = synth(&[]);
    assert!(stdout.contains("cache hit"), "{stdout}");
    assert_eq!(first, second);
    let (stdout, third) = synth(&["--no-cache"]);
    assert!(stdout.contains("cache off"), "{stdout}");
    assert_eq!(first, third);
    let image = image::open(&out).unwrap();
    assert_eq!((image.width(), image.height()), (48, 32));
    let coords = image::open(dir.path().join("terra.coords.png")).unwrap();
    assert_eq!((coords.width(), coords.height()), (48, 32));
    // Only the two PNGs: no temporary file is left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn synth_names_a_bad_exemplar_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let tiny = dir.path().join("tiny.png");
    image::RgbImage::new(8, 8).save(&tiny).unwrap();
    let out = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("synth").arg(&tiny).arg("-o").arg(&out));
    assert!(!ok);
    assert!(
        err.contains("tiny.png") && err.contains("8x8") && err.contains("at least 16"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists());
    // An empty cache folder variable is refused by name, before any work.
    let terra = repo("assets/exemplars/terra.pat");
    let (ok, _, err) = run(lazysolid()
        .arg("synth")
        .arg(&terra)
        .arg("-o")
        .arg(&out)
        .env("LAZYSOLID_CACHE_DIR", ""));
    assert!(!ok && err.contains("LAZYSOLID_CACHE_DIR"), "{err}");
    assert!(!out.exists());
}

#[test]
fn bench_synth_writes_its_tables_files_and_images() {
    let exemplars = repo("assets/exemplars");
    assert!(
        exemplars.join("leather.pat").exists(),
        "{} is missing: run scripts/fetch-assets.sh",
        exemplars.display()
    );
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "synth", "--exemplars", "leather", "--res", "64x64"])
            .args(["--energy-samples", "256", "--runs", "1", "--warmup", "0"])
            .args(["--quality-seeds", "2"])
            .arg("--exemplar-dir")
            .arg(&exemplars),
        out.path(),
        &[
            "leather 64x64 analysis",
            "leather 64x64 -> 64x64",
            "lazysolid gpu passes (timestamps)",
            "lazysolid end-to-end cold (wall)",
            "lazysolid end-to-end warm (wall)",
            "texture-synthesis 0.8.2 (2 threads)",
            "energy lazysolid",
            "mean of 2 seed(s)",
            "gpu profile",
            "target leather 64x64 -> 64x64: >= 20x faster",
        ],
    );
    // The analysis row and five rows of the one case.
    assert_eq!(bench.csv().1.len(), 1 + 5);
    let json = bench.json();
    let derived = &json["derived"];
    for key in [
        "leather 64x64 -> 64x64: lazysolid energy",
        "leather 64x64 -> 64x64: texture-synthesis energy",
        "leather 64x64 -> 64x64: lazysolid histogram distance",
        "leather 64x64 -> 64x64: texture-synthesis histogram distance",
        "leather 64x64 -> 64x64: lazysolid period repetition",
        "leather 64x64 -> 64x64: texture-synthesis period repetition",
    ] {
        let v = derived[key].as_f64().unwrap_or_else(|| panic!("no {key}"));
        assert!(v.is_finite() && v >= 0.0, "{key} = {v}");
    }
    // The mean lies within the range of the two seeds' energies, for both synthesizers.
    for who in ["lazysolid", "texture-synthesis"] {
        let get = |key: &str| {
            let key = format!("leather 64x64 -> 64x64: {who} {key}");
            derived[&key].as_f64().unwrap_or_else(|| panic!("no {key}"))
        };
        let (lo, mean, hi) = (get("energy min"), get("energy"), get("energy max"));
        assert!(lo <= mean && mean <= hi, "{who}: {lo} {mean} {hi}");
    }
    assert_eq!(derived["quality seeds"], 2.0);
    // 58² interior positions on the coarsest subgrid with at most 256: every 4th, 15².
    assert_eq!(derived["leather 64x64 -> 64x64: energy samples"], 225.0);
    let ratio = json["rows"][1]["ratio"].as_f64().expect("a ratio");
    assert!(ratio > 0.0, "{ratio}");
    let figures = bench.figures();
    let names = bench.figure_names();
    for f in [
        "leather-64-lazysolid-vs-texture-synthesis.png",
        "synth-times.png",
    ] {
        assert!(names.iter().any(|n| n == f), "missing {f} in {names:?}");
    }
    assert!(!names.iter().any(|n| n.contains("partial")), "{names:?}");
    let side = image::open(figures.join("leather-64-lazysolid-vs-texture-synthesis.png")).unwrap();
    assert_eq!((side.width(), side.height()), (2 * 64 + 8, 64));
}

#[test]
fn bench_synth_refuses_missing_exemplars_and_bad_sizes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--res", "4"]));
    assert!(
        !ok && err.contains("--res 4x4 is out of range (7..=2048 per side)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--res", "64x32"]));
    assert!(
        !ok && err.contains("--res 64x32") && err.contains("square"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "synth", "--quality-seeds", "0"]));
    assert!(
        !ok && err.contains("--quality-seeds 0 is out of range (1..=16)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "synth",
        "--exemplars",
        "no-such-pattern",
        "--exemplar-dir",
        "/no/such/dir",
    ]));
    assert!(
        !ok && err.contains("/no/such/dir/no-such-pattern.pat") && err.contains("fetch-assets"),
        "{err}"
    );
}

#[test]
fn bench_textures_writes_the_table_pictures_and_files() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "textures", "--voxel-res", "64", "--res", "64x64"])
            .args(["--runs", "1", "--warmup", "0", "--mesh"])
            .arg(repo("assets/meshes/bunny00.off")),
        out.path(),
        &[
            "Table 4.1 on",
            "octree 8·8 (nearest)",
            "octree 4·4·4 (8 descents)",
            "coherent hash (8 lookups)",
            "perfect hash (nearest)",
            "perfect hash blocked, b = ",
            "tiletree (bilinear, 1 fetch)",
            "stands for the thesis' octree texture, 8 lookups (Table 4.1)",
        ],
    );
    let json = bench.json();
    // --builder auto: the perfect hash (texel layout) is built on the host on a CPU device,
    // on the GPU otherwise; the blocked layout always on the host; other rows name none.
    let auto = if json["run"]["device_type"] == "cpu" {
        "cpu"
    } else {
        "gpu"
    };
    for row in json["rows"].as_array().unwrap() {
        let implementation = row["implementation"].as_str().unwrap();
        let expected = if implementation.starts_with("perfect hash blocked") {
            Some("cpu")
        } else if implementation.starts_with("perfect hash") {
            Some(auto)
        } else {
            None
        };
        assert_eq!(row["builder"].as_str(), expected, "{implementation}");
    }
    let derived = json["derived"].as_object().unwrap();
    let seen = derived["viewpoint surface points"].as_f64().unwrap();
    assert!(seen > 500.0, "{seen}");
    // The voxelization is conservative: every point the camera sees lies in stored texels.
    let missing: Vec<_> = derived
        .iter()
        .filter(|(k, _)| k.ends_with("points not stored"))
        .collect();
    assert_eq!(missing.len(), 2 * 6 + 1, "{missing:?}");
    assert!(
        missing.iter().all(|(_, v)| v.as_f64() == Some(0.0)),
        "{missing:?}"
    );
    let figures = bench.figures();
    let picture = |name: &str| image::open(figures.join(name)).unwrap().to_rgb8();
    for f in [
        "textures-memory.png",
        "textures-speed.png",
        "tiletree-tile-map.png",
    ] {
        assert!(figures.join(f).exists(), "missing {f}");
    }
    // The same texels through different structures: nearest pictures are identical, trilinear
    // ones agree to float rounding.
    for other in ["coherent-hash-nearest.png", "perfect-hash-nearest.png"] {
        assert_eq!(picture("octree-8-8-nearest.png"), picture(other), "{other}");
    }
    let a = picture("octree-8-8-8-descents.png");
    assert_eq!(a.dimensions(), (64, 64));
    for other in ["coherent-hash-8-lookups.png", "perfect-hash-8-lookups.png"] {
        let worst = a
            .as_raw()
            .iter()
            .zip(picture(other).as_raw())
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap();
        assert!(worst <= 1, "{other}: {worst}");
    }
    // The TileTree samples the surface where the volume stores sample voxel centres: close to
    // the trilinear picture (FLIP), closer than the nearest one is.
    let flip = |a: &str, b: &str| {
        let (ok, out, err) = run(lazysolid()
            .arg("diff")
            .arg(figures.join(a))
            .arg(figures.join(b)));
        assert!(ok, "{err}");
        let mean = out
            .lines()
            .find_map(|l| l.strip_prefix("FLIP mean"))
            .unwrap_or_else(|| panic!("no FLIP mean in {out}"));
        mean.trim().parse::<f64>().unwrap()
    };
    let tile = flip("octree-8-8-8-descents.png", "tiletree-bilinear-1-fetch.png");
    let nearest = flip("octree-8-8-8-descents.png", "octree-8-8-nearest.png");
    assert!(
        tile < 0.05 && tile < nearest,
        "tiletree {tile}, nearest {nearest}"
    );
}

#[test]
fn bench_textures_refuses_bad_resolutions_views_and_meshes() {
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--res", "8x8"]));
    assert!(
        !ok && err.contains("--res 8x8 is out of range (16..=4096 per side)"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--mesh", "/no/such/mesh.off"]));
    assert!(!ok && err.contains("/no/such/mesh.off"), "{err}");
    let (ok, _, err) = run(lazysolid()
        .args(["bench", "textures", "--voxel-res", "100000", "--mesh"])
        .arg(repo("assets/meshes/cube.off")));
    assert!(!ok && err.contains("100000"), "{err}");
    let (ok, _, err) = run(lazysolid()
        .args([
            "bench",
            "textures",
            "--voxel-res",
            "64",
            "--octree",
            "8.4",
            "--mesh",
        ])
        .arg(repo("assets/meshes/cube.off")));
    assert!(!ok && err.contains("--octree \"8.4\""), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bench_psh_writes_its_table_files_and_figures() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "psh", "--quick", "--runs", "1", "--warmup", "0"])
            .args(["--builder", "gpu", "--mesh", "armadillo"]),
        out.path(),
        &[
            "random-2d build",
            "cpu reference (1 thread)",
            "gpu construction",
            "voxels-128 query",
            "coherent hash lf 0.85 (gpu)",
            "dense array (gpu)",
            "blocked R=64: chosen b",
        ],
    );
    let json = bench.json();
    // Each build row names its construction; the perfect hash's queries read the table of
    // --builder gpu; the other structures name none.
    for row in json["rows"].as_array().unwrap() {
        let expected = match row["implementation"].as_str().unwrap() {
            "cpu reference (1 thread)" => Some("cpu"),
            "gpu construction" | "perfect hash (gpu)" => Some("gpu"),
            _ => None,
        };
        assert_eq!(row["builder"].as_str(), expected, "{row}");
    }
    assert!(bench.column("builder").iter().any(|b| b == "gpu"));
    let derived = &json["derived"];
    // The GPU construction ends at the CPU reference's sizes on every dataset.
    for set in ["random-2d", "image", "voxels-128"] {
        let get = |k: &str| {
            derived[format!("{set}: {k}")]
                .as_f64()
                .unwrap_or_else(|| panic!("no {set}: {k}"))
        };
        assert_eq!(
            get("cpu |Phi| per axis"),
            get("gpu |Phi| per axis"),
            "{set}"
        );
        let bits = get("gpu Phi bits per key");
        assert!(bits > 0.0 && bits.is_finite(), "{set}: {bits}");
    }
    let figures = bench.figures();
    for f in [
        "psh-construction.png",
        "psh-queries.png",
        "psh-blocked-bytes.png",
    ] {
        assert!(figures.join(f).exists(), "missing {f}");
    }
}

/// The revision `lazysolid --version` reports: the one its result files record.
fn version_revision() -> String {
    let (ok, version, err) = run(lazysolid().arg("--version"));
    assert!(ok, "{err}");
    version
        .split("(revision ")
        .nth(1)
        .and_then(|r| r.trim().strip_suffix(')'))
        .unwrap_or_else(|| panic!("no revision in {version:?}"))
        .to_string()
}

#[test]
fn the_version_is_the_build_revision_of_the_checkout() {
    let revision = version_revision();
    let head = Command::new("git")
        .args(["rev-parse", "--short=12", "HEAD"])
        .current_dir(repo("."))
        .output();
    match head {
        Ok(out) if out.status.success() => {
            let head = String::from_utf8_lossy(&out.stdout).trim().to_string();
            assert!(
                revision == head || revision == format!("{head}-dirty"),
                "{revision} against HEAD {head}"
            );
        }
        // Not a git checkout: the build says so rather than guessing.
        _ => assert_eq!(revision, "unknown"),
    }
}

#[test]
fn bench_results_record_the_revision_once_per_row() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "prims", "--quick", "--scan-elements", "4096"])
            .args(["--sort-elements", "1024", "--runs", "1", "--warmup", "0"]),
        out.path(),
        &[],
    );
    let revision = version_revision();
    assert_eq!(bench.json()["run"]["revision"], revision.as_str());
    let column = bench.column("revision");
    assert!(
        !column.is_empty() && column.iter().all(|r| *r == revision),
        "{column:?}"
    );
    assert!(bench.stdout.contains(&format!("revision {revision}")));
}

/// The help of the tool and of every subcommand.
fn every_help() -> Vec<(String, String)> {
    let commands: [&[&str]; 20] = [
        &[],
        &["device"],
        &["diff"],
        &["render"],
        &["synth"],
        &["multiscale"],
        &["zoom"],
        &["fracture"],
        &["solid"],
        &["bench", "prims"],
        &["bench", "hash"],
        &["bench", "psh"],
        &["bench", "trace"],
        &["bench", "synth"],
        &["bench", "textures"],
        &["bench", "glints"],
        &["bench", "solid"],
        &["bench", "lazy"],
        &["bench", "cuts"],
        &["bench", "multiscale"],
    ];
    commands
        .iter()
        .map(|c| {
            let (ok, help, err) = run(lazysolid().args(*c).arg("--help"));
            assert!(ok, "{c:?}: {err}");
            (c.join(" "), help)
        })
        .collect()
}

#[test]
fn every_help_uses_one_word_and_one_value_form_per_thing() {
    // Flag → value name, over every subcommand: one form per flag.
    let mut forms: std::collections::BTreeMap<String, std::collections::BTreeSet<String>> =
        Default::default();
    for (command, help) in every_help() {
        // Flag lines only (`  -o, --output <OUTPUT>`), not flags named in prose.
        for line in help.lines().filter(|l| l.trim_start().starts_with('-')) {
            // The flags and their value names lead the line; the description after them may
            // name other flags in prose (`... from --seed`).
            let words: Vec<&str> = line
                .split_whitespace()
                .take_while(|w| w.starts_with('-') || w.starts_with('<'))
                .collect();
            for (i, w) in words.iter().enumerate() {
                let flag = w.trim_end_matches(',');
                if flag.starts_with("--") && flag.len() > 2 {
                    let value = words
                        .get(i + 1)
                        .filter(|v| v.starts_with('<'))
                        .map_or("(switch)", |v| v);
                    forms
                        .entry(flag.to_string())
                        .or_default()
                        .insert(value.to_string());
                }
            }
        }
        for old in [
            "--view",
            "--size ",
            "--sizes",
            "--voxel-resolution",
            "--image-size",
            "--blocked-resolution",
            "--out <",
            "--quality-size",
        ] {
            assert!(!help.contains(old), "`{command}` still says {old}:\n{help}");
        }
    }
    for (flag, values) in &forms {
        assert_eq!(values.len(), 1, "{flag} is written {values:?}");
    }
    let form = |flag: &str| forms[flag].iter().next().unwrap().clone();
    assert_eq!(form("--res"), "<WxH>");
    assert_eq!(form("--image-res"), "<WxH>");
    assert_eq!(form("--voxel-res"), "<N>");
    assert_eq!(form("--mesh"), "<NAME|PATH>");
    assert_eq!(form("--exemplars"), "<NAME|PATH>");
    assert_eq!(form("--out-dir"), "<DIR>");
    assert_eq!(form("--builder"), "<BUILDER>");
    assert_eq!(form("--validation"), "(switch)");
}

#[test]
fn renamed_flags_are_refused_by_name() {
    for (args, old, new) in [
        (
            &["bench", "textures", "--view", "64"][..],
            "--view",
            "--res",
        ),
        (
            &["bench", "hash", "--voxel-resolution", "32"],
            "--voxel-resolution",
            "--voxel-res",
        ),
        (
            &["bench", "hash", "--image-size", "256"],
            "--image-size",
            "--image-res",
        ),
        (
            &["bench", "psh", "--voxel-resolutions", "64"],
            "--voxel-resolutions",
            "--voxel-res",
        ),
        (
            &["bench", "psh", "--blocked-resolution", "64"],
            "--blocked-resolution",
            "--blocked-voxel-res",
        ),
        (&["bench", "synth", "--sizes", "64"], "--sizes", "--res"),
        (
            &["bench", "prims", "--out", "results"],
            "--out",
            "--out-dir",
        ),
        (
            &["synth", "terra", "-o", "x.png", "--size", "64"],
            "--size",
            "--res",
        ),
        (
            &["solid", "terra", "-o", "x.nrrd", "--size", "64"],
            "--size",
            "--voxel-res",
        ),
        (
            &["bench", "solid", "--sizes", "64"],
            "--sizes",
            "--voxel-res",
        ),
        (&["multiscale", "g.toml", "--size", "64"], "--size", "--res"),
        (
            &["zoom", "g.toml", "--frames", "3"],
            "--frames",
            "--frame-count",
        ),
        (&["zoom", "g.toml", "-o", "frames"], "-o", "--out-dir"),
        (
            &["fracture", "cube", "--pieces", "2", "-o", "pieces"],
            "-o",
            "--out-dir",
        ),
        (
            &["bench", "multiscale", "--quality-size", "64"],
            "--quality-size",
            "--quality-res",
        ),
    ] {
        let out = lazysolid().args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(&format!("unexpected argument '{old}'"))
                && err.contains(&format!("`{old}` is now `{new}`")),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn meshes_are_found_by_name_from_any_folder() {
    let elsewhere = tempfile::tempdir().unwrap();
    let out = elsewhere.path().join("results");
    let bench = BenchRun::new(
        lazysolid()
            .current_dir(elsewhere.path())
            .args(["bench", "trace", "--mesh", "cube", "--res", "16x16"])
            .args(["--runs", "1", "--warmup", "0"]),
        &out,
        &["primary rays", "gpu cwbvh two-level"],
    );
    // The cube of the assets: its 12 triangles.
    let faces: f64 = std::fs::read_to_string(repo("assets/meshes/cube.off"))
        .unwrap()
        .lines()
        .nth(1)
        .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
        .unwrap();
    assert_eq!(bench.json()["derived"]["triangles"], faces);

    // An unknown name lists the known ones and where it looked.
    let (ok, _, err) = run(lazysolid()
        .current_dir(elsewhere.path())
        .args(["bench", "trace", "--mesh", "dragon"]));
    assert!(
        !ok && err.contains("--mesh dragon: no mesh named \"dragon\"")
            && err.contains("armadillo")
            && err.contains("bunny00"),
        "{err}"
    );

    // LAZYSOLID_ASSETS comes first: a folder holding only `tiny` knows no cube.
    let assets = elsewhere.path().join("my-assets");
    std::fs::create_dir_all(assets.join("meshes")).unwrap();
    std::fs::copy(
        repo("assets/meshes/cube.off"),
        assets.join("meshes/tiny.off"),
    )
    .unwrap();
    let (ok, _, err) = run(lazysolid()
        .env("LAZYSOLID_ASSETS", &assets)
        .args(["bench", "trace", "--mesh", "cube"]));
    assert!(
        !ok && err.contains("known: tiny") && err.contains("my-assets"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid()
        .env("LAZYSOLID_ASSETS", elsewhere.path().join("nowhere"))
        .args(["bench", "trace", "--mesh", "cube"]));
    assert!(
        !ok && err.contains("LAZYSOLID_ASSETS=") && err.contains("nowhere"),
        "{err}"
    );
}

/// Runs `c` with `-v` (which announces the device as soon as one is created); it must fail
/// within seconds, before any device exists, with an error that names every one of `needles`.
fn fails_before_any_device(c: &mut Command, needles: &[&str]) {
    let start = std::time::Instant::now();
    let out = c
        .arg("-v")
        .env("LAZYSOLID_VALIDATION", "1")
        .output()
        .unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    for needle in needles {
        assert!(err.contains(needle), "missing {needle:?} in {err}");
    }
    assert!(!err.contains("device "), "a device was created: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(seconds < 10.0, "{seconds} s");
}

#[test]
fn unwritable_outputs_fail_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let scene = repo("scenes/test/interior.toml");
    let missing = dir.path().join("no-such-folder").join("out.png");
    let missing_text = missing.display().to_string();
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(&missing),
        &[&missing_text, "does not exist"],
    );
    // The EXR beside a writable PNG is checked too.
    let exr = dir.path().join("no-such-folder").join("out.exr");
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(dir.path().join("out.png"))
            .arg("--exr")
            .arg(&exr),
        &["--exr", &exr.display().to_string()],
    );
    // A folder is not a file.
    fails_before_any_device(
        lazysolid()
            .arg("render")
            .arg(&scene)
            .arg("-o")
            .arg(dir.path()),
        &["is a folder"],
    );
    fails_before_any_device(
        lazysolid()
            .arg("synth")
            .arg("terra")
            .arg("-o")
            .arg(&missing),
        &[&missing_text],
    );
    // A results folder below a file.
    let file = dir.path().join("a-file");
    std::fs::write(&file, "").unwrap();
    fails_before_any_device(
        lazysolid()
            .args(["bench", "prims", "--quick", "--out-dir"])
            .arg(file.join("results")),
        &["--out-dir", "a-file", "is not a folder"],
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "nothing written"
    );
}

#[test]
fn bench_textures_refuses_store_and_filter_choices_that_measure_nothing() {
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "textures",
        "--stores",
        "perfect-blocked",
        "--filters",
        "nearest",
    ]));
    assert!(!ok && err.contains("trilinear"), "{err}");
    let (ok, _, err) = run(lazysolid().args(["bench", "textures", "--stores", "kd-tree"]));
    assert!(
        !ok && err.contains("'kd-tree'")
            && err.contains("octree, hash, perfect, perfect-blocked, tiletree"),
        "{err}"
    );
    let (ok, _, err) = run(lazysolid().args(["bench", "psh", "--builder", "fpga"]));
    assert!(
        !ok && err.contains("'fpga'") && err.contains("auto, cpu, gpu"),
        "{err}"
    );
}

/// A `side`² PNG cut from the top-left of GIMP's terra pattern, in `dir`.
fn terra_square(dir: &std::path::Path, side: u32) -> std::path::PathBuf {
    let full = image::open(repo("assets/exemplars/terra.pat"))
        .map(|i| i.to_rgb8())
        .unwrap_or_else(|_| {
            // The image crate does not read GIMP patterns: decode through the library.
            let e = lazysolid_synth::Exemplar::load(&repo("assets/exemplars/terra.pat")).unwrap();
            image::RgbImage::from_fn(e.width, e.height, |x, y| image::Rgb(e.at(x, y)))
        });
    let path = dir.join(format!("terra{side}.png"));
    image::imageops::crop_imm(&full, 0, 0, side, side)
        .to_image()
        .save(&path)
        .unwrap();
    path
}

#[test]
fn solid_writes_volume_slices_and_slab_with_metrics() {
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let out_dir = dir.path().join("out");
    std::fs::create_dir(&out_dir).unwrap();
    let out = out_dir.join("terra.nrrd");
    let cache = dir.path().join("cache");
    let solid = |extra: &[&str]| {
        run(lazysolid()
            .arg("solid")
            .args(extra)
            .arg(&exemplar)
            // One correction pass (the defaults' cost a few times more on lavapipe); the
            // synthesizer itself is tested in tests/tests/solid.rs.
            .args([
                "--voxel-res",
                "64",
                "--offset",
                "-70,5,9",
                "--seed",
                "4",
                "--passes",
                "1",
            ])
            .args(["--energy-samples", "64", "-o"])
            .arg(&out)
            .env("LAZYSOLID_CACHE_DIR", &cache)
            .env("LAZYSOLID_VALIDATION", "1"))
    };
    let (ok, stdout, err) = solid(&[]);
    assert!(ok, "{err}");
    for needle in [
        // On lavapipe (a CPU device) the candidates are computed on the host.
        "candidates (host)",
        "synthesis (GPU)",
        "peak GPU memory",
        "triples: 100.0 % are candidates of their pixel",
        "slice perpendicular to z vs E_z: SWD",
        "blockiness",
        "period repetition",
        "energy",
        "gradient anisotropy (u - v)/(u + v): exemplars ",
        "every volume has x - y + z = 0",
        "render (GPU)",
        "feature channel of ",
        "% of the pixels, distance clamped at 4 px, deviation ",
    ] {
        assert!(stdout.contains(needle), "missing {needle:?} in:\n{stdout}");
    }
    let nrrd = std::fs::read(&out).unwrap();
    let header_end = nrrd.windows(2).position(|w| w == b"\n\n").unwrap() + 2;
    assert!(nrrd.starts_with(b"NRRD0004\n"));
    assert_eq!(nrrd.len() - header_end, 64 * 64 * 64 * 3);
    for (name, width) in [
        ("x", 64),
        ("y", 64),
        ("z", 64),
        ("oblique", 64),
        ("slab", 9 * 16 + 8 * 2),
        ("render", 400),
        // Exemplar | mask | distance.
        ("features", 3 * 16 + 2 * 4),
    ] {
        let image = image::open(out_dir.join(format!("terra.{name}.png"))).unwrap();
        assert_eq!(image.width(), width, "{name}");
    }
    // The carved render's scene names the volume beside it and loads.
    let scene = out_dir.join("terra.scene.toml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains("path = \"terra.nrrd\""), "{text}");
    lazysolid_renderer::scene::Scene::load(&scene).unwrap();
    // The volume, seven pictures and the scene; no temporary file is left behind.
    assert_eq!(std::fs::read_dir(&out_dir).unwrap().count(), 9);
    assert!(stdout.contains("cache miss"), "{stdout}");
    // A second run reads the candidates back and writes the same volume.
    let (ok, stdout, err) = solid(&["--no-render"]);
    assert!(ok, "{err}");
    assert!(stdout.contains("cache hit"), "{stdout}");
    assert_eq!(std::fs::read(&out).unwrap(), nrrd);
}

#[test]
fn solid_names_each_bad_input_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let good = terra_square(dir.path(), 16);
    // Any image from 16 pixels a side up is fitted (tools/tests/cli_photos.rs); what is left
    // to refuse: smaller images, images past the decode limit, a crop that does not fit, an
    // exemplar side that is no power of two in 16..=256.
    let tiny = dir.path().join("tiny.png");
    image::RgbImage::new(8, 8).save(&tiny).unwrap();
    let huge = dir.path().join("huge.png");
    image::RgbImage::new(9000, 16).save(&huge).unwrap();
    let corrupt = dir.path().join("corrupt.png");
    std::fs::write(&corrupt, b"not a PNG at all").unwrap();
    let out = dir.path().join("out.nrrd");
    let path = |p: &std::path::Path| p.to_str().unwrap().to_owned();
    let cases: [(Vec<String>, &[&str]); 15] = [
        (
            vec!["--ey".into(), path(&tiny)],
            &["tiny.png", "8x8", "at least 16"],
        ),
        (
            vec!["--ex".into(), path(&huge)],
            &["huge.png", "9000x16", "8192"],
        ),
        (
            vec![
                "--fit".into(),
                "crop".into(),
                "--exemplar-side".into(),
                "32".into(),
            ],
            &["terra16.png", "--fit crop", "32x32"],
        ),
        (
            vec!["--exemplar-side".into(), "24".into()],
            &["--exemplar-side 24", "power of two"],
        ),
        (
            vec!["--exemplar-side".into(), "512".into()],
            &["--exemplar-side 512", "16..=256"],
        ),
        (
            vec!["--fit".into(), "stretch".into()],
            &["'stretch'", "auto, crop, resample"],
        ),
        (
            vec!["--ez".into(), "/nonexistent/e.png".into()],
            &["/nonexistent/e.png", "cannot read"],
        ),
        (
            vec!["--ey".into(), path(&corrupt)],
            &["corrupt.png", "cannot decode"],
        ),
        (
            vec!["--voxel-res".into(), "100".into()],
            &["--voxel-res 100", "64, 128, 256"],
        ),
        (
            vec!["--voxel-res".into(), "512".into()],
            &["--voxel-res 512", "64, 128, 256"],
        ),
        (
            vec!["--offset".into(), "300000000,0,0".into()],
            &["--offset 300000000,0,0", "268435456"],
        ),
        (vec!["--strip".into(), "4".into()], &["strip", "odd"]),
        (vec!["--s".into(), "80".into()], &["`s`", "1..=65"]),
        (
            vec!["--balance".into(), "65".into()],
            &["`balance`", "0..=64"],
        ),
        (
            vec!["--feature-weight".into(), "401".into()],
            &["--feature-weight", "401", "0..=400"],
        ),
    ];
    for (extra, needles) in cases {
        let (ok, _, err) = run(lazysolid()
            .arg("solid")
            .arg(&good)
            .args(&extra)
            .arg("-o")
            .arg(&out));
        assert!(!ok, "{extra:?}");
        for needle in needles {
            assert!(
                err.contains(needle),
                "{extra:?}: missing {needle:?} in {err}"
            );
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!out.exists());
    }
    let png_out = dir.path().join("out.png");
    let (ok, _, err) = run(lazysolid().arg("solid").arg(&good).arg("-o").arg(&png_out));
    assert!(!ok && err.contains(".nrrd"), "{err}");
    assert!(!png_out.exists());
    // Nothing but the inputs in the folder.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 4);
}

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
                "--exemplars",
                "terra",
                "--three",
                "",
            ])
            .args([
                "--candidate-sides",
                "16",
                "--side",
                "16",
                "--voxel-res",
                "16",
            ])
            .args(["--passes", "1", "--energy-samples", "64"])
            .args(["--runs", "1", "--warmup", "0"]),
        out.path(),
        &[
            "terra 16² candidates",
            "lazysolid gpu kernels (wall)",
            "lazysolid host, pruned (wall)",
            "lazysolid gpu synthesis (wall)",
            "lazysolid end-to-end cold (wall)",
            "lazysolid end-to-end warm (wall)",
            "terra 16³ peak GPU MiB",
            "own role",
            "mean colour",
            "keep current",
            "crossbar only",
            "no balance",
            "no feature",
            "extruded E_z",
            "2d synth",
            // The 64² pattern fitted to the 16² measured (--fit auto).
            "terra: exemplar fit: terra.pat 64x64 RGB → Lanczos3 resample 16x16",
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
        "terra.pat 64x64 RGB → Lanczos3 resample 16x16"
    );
    let quality = std::fs::read_to_string(figures.join("quality.csv")).unwrap();
    // Nine variants, three axes each, plus the header.
    assert_eq!(quality.lines().count(), 1 + 9 * 3, "{quality}");
    assert!(
        quality
            .lines()
            .next()
            .unwrap()
            .contains(",anisotropy,exemplar_anisotropy,"),
        "{quality}"
    );
    for name in [
        "terra-16-slices.png",
        "terra-16-keep-current-slices.png",
        "terra-16-no-balance-slices.png",
        "terra-16-no-feature-slices.png",
        "terra-slab.png",
        "quality.json",
    ] {
        assert!(figures.join(name).exists(), "{name}");
    }
    assert!(bench.stdout.contains("quality table"), "{}", bench.stdout);
}

/// `bench solid --no-ablations`: the default synthesis, the colour rules, the extruded
/// reference and the 2D synthesis are scored; none of the four ablation volumes is made.
#[test]
fn bench_solid_without_ablations_scores_the_default_only() {
    let out = tempfile::tempdir().unwrap();
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "solid",
                "--quick",
                "--no-ablations",
                "--exemplars",
                "terra",
            ])
            .args(["--three", "", "--builders", "host"])
            .args([
                "--candidate-sides",
                "16",
                "--side",
                "16",
                "--voxel-res",
                "16",
            ])
            .args(["--passes", "1", "--energy-samples", "64"])
            .args(["--runs", "1", "--warmup", "0"]),
        out.path(),
        &["own role", "mean colour", "extruded E_z", "2d synth"],
    );
    for absent in ["keep current", "crossbar only", "no balance", "no feature"] {
        assert!(
            !bench.stdout.contains(absent),
            "{absent}:\n{}",
            bench.stdout
        );
    }
    let figures = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder");
    let quality = std::fs::read_to_string(figures.join("quality.csv")).unwrap();
    // Five variants, three axes each, plus the header.
    assert_eq!(quality.lines().count(), 1 + 5 * 3, "{quality}");
    assert!(figures.join("terra-16-slices.png").exists());
    assert!(!figures.join("terra-16-keep-current-slices.png").exists());
}

/// `bench lazy` on the bunny at 16³ with a 16² terra crop (its candidates take seconds): the
/// timed row, the per-level notes, each store's bytes and the cross-section figure.
#[test]
fn bench_lazy_writes_voxels_stores_and_a_cross_section() {
    let out = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let bench = BenchRun::new(
        lazysolid()
            .args(["bench", "lazy", "--meshes", "bunny00", "--voxel-res", "16"])
            .arg("--exemplar")
            .arg(&exemplar)
            .args(["--runs", "1", "--warmup", "0"])
            .env("LAZYSOLID_CACHE_DIR", dir.path().join("cache")),
        out.path(),
        &[
            "bunny00 16³",
            "gpu lazy (wall)",
            "bunny00 16³: finest-level voxels synthesized % of R³",
            "bunny00 16³: store MB: tiletree",
            "bunny00 16³: store MB: perfect hash (trilinear)",
            "bunny00 16³: level 0 voxels",
            "bunny00 16³ cross-section z = 8: voxel versions computed after the surface",
        ],
    );
    let figures = bench
        .entries
        .iter()
        .find(|p| p.is_dir())
        .expect("a figures folder");
    let section = image::open(figures.join("bunny00-16-section-z8.png")).unwrap();
    assert_eq!((section.width(), section.height()), (16, 16));
    assert!(bench.json()["rows"]
        .as_array()
        .is_some_and(|r| r.len() == 1));
}

/// `lazysolid fracture` writes closed pieces (each OBJ read back and checked) with the cut faces
/// in their own group and material and volumes that add up to the mesh's; plane cuts report a
/// plane that misses; open meshes, bad piece counts and bad planes are refused clearly, and
/// a refused run writes nothing.
#[test]
fn fracture_writes_closed_obj_pieces_and_refuses_bad_input() {
    use lazysolid_renderer::fracture::{check_closed, volume};
    use lazysolid_renderer::mesh::Mesh;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pieces");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "elephant",
            "--pieces",
            "6",
            "--seed",
            "4",
            "--out-dir",
        ])
        .arg(&out));
    assert!(ok, "{err}");
    assert!(stdout.contains("6 pieces of"), "{stdout}");
    let whole = Mesh::load(repo("assets/meshes/elephant.off")).unwrap();
    let mut sum = 0.0;
    for i in 0..6 {
        let path = out.join(format!("piece_{i:03}.obj"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("mtllib fragments.mtl"), "{text:.200}");
        assert!(text.contains("g interior\nusemtl interior\n"), "piece {i}");
        assert!(text.contains("g surface\nusemtl surface\n"), "piece {i}");
        let piece = Mesh::load(&path).unwrap();
        check_closed(&piece).unwrap();
        sum += volume(&piece.positions, &piece.triangles);
    }
    assert!(!out.join("piece_006.obj").exists());
    let v = volume(&whole.positions, &whole.triangles);
    assert!(((sum - v) / v).abs() < 1e-5, "{sum} vs {v}");
    let mtl = std::fs::read_to_string(out.join("fragments.mtl")).unwrap();
    assert!(mtl.contains("newmtl interior") && mtl.contains("newmtl surface"));

    let cut = dir.path().join("cut");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "cube",
            "--plane",
            "0,1,0,5",
            "--plane",
            "1,0,0,0.5",
            "--out-dir",
        ])
        .arg(&cut));
    assert!(ok, "{err}");
    assert!(stdout.contains("(plane 1) misses the mesh"), "{stdout}");
    assert!(
        stdout.contains("75.0000 %") && stdout.contains("25.0000 %"),
        "{stdout}"
    );

    let refused = dir.path().join("refused");
    for (args, needles) in [
        (
            vec!["fracture", "ChineseDragon-10kv", "--pieces", "4"],
            vec!["ChineseDragon-10kv.off", "not closed", "6 boundary edge"],
        ),
        (
            vec!["fracture", "cube", "--pieces", "0"],
            vec!["--pieces 0", "1 to 1024"],
        ),
        (
            vec!["fracture", "cube", "--plane", "0,0,0,1"],
            vec!["non-zero normal"],
        ),
        (vec!["fracture", "cube"], vec!["--pieces N", "--plane"]),
        (
            vec!["fracture", "no_such_mesh", "--pieces", "2"],
            vec!["no_such_mesh"],
        ),
    ] {
        let (ok, _, err) = run(lazysolid().args(&args).arg("--out-dir").arg(&refused));
        assert!(!ok, "{args:?} must fail");
        for n in needles {
            assert!(err.contains(n), "{args:?}: {n:?} not in {err}");
        }
        assert!(!refused.exists(), "{args:?} wrote {}", refused.display());
    }
}

/// `render --frame K --frames A..B` renders the still and the sequence from one bake: the still
/// (PNG and EXR), numbered PNGs, and an animated GIF with one image per frame. A scene without
/// [animation] and a frame past its last are refused before anything is rendered.
#[test]
fn render_frames_writes_a_still_numbered_frames_and_a_gif() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("boom.png");
    let (ok, stdout, err) = run(lazysolid()
        .arg("render")
        .arg(repo("scenes/test/fracture.toml"))
        .args([
            "--frame", "1", "--frames", "0..2", "--res", "32x24", "--spp", "2", "-o",
        ])
        .arg(&out)
        .env("LAZYSOLID_VALIDATION", "1"));
    assert!(ok, "{err}");
    for needle in [
        "cut faces:",
        "frame 1 (t = 0.250 s): 32x24, 2 spp",
        "frame 2 (t = 0.500 s)",
        "total",
    ] {
        assert!(err.contains(needle), "{needle:?} not in {err}");
    }
    assert!(
        stdout.contains("animation:") && stdout.contains("boom.gif"),
        "{stdout}"
    );
    for f in [
        "boom.png",
        "boom.exr",
        "boom_0000.png",
        "boom_0001.png",
        "boom_0002.png",
    ] {
        assert!(dir.path().join(f).is_file(), "{f} missing");
    }
    assert!(!dir.path().join("boom_0003.png").exists());
    let gif = std::fs::read(dir.path().join("boom.gif")).unwrap();
    assert!(gif.starts_with(b"GIF89a"));
    // One graphic control extension (the frame delay) per frame.
    let frames = gif.windows(2).filter(|w| w == &[0x21, 0xf9]).count();
    assert_eq!(frames, 3, "GIF frames");

    let refused = dir.path().join("refused.png");
    for (scene, args, needle) in [
        (
            "scenes/test/synthesized.toml",
            vec!["--frames", "0..1"],
            "has no [animation]",
        ),
        (
            "scenes/test/fracture.toml",
            vec!["--frame", "4"],
            "frame 4 is past the scene's last frame 3",
        ),
        (
            "scenes/test/fracture.toml",
            vec!["--frames", "2..1"],
            "the first frame is after the last",
        ),
    ] {
        let (ok, _, err) = run(lazysolid()
            .arg("render")
            .arg(repo(scene))
            .args(&args)
            .arg("-o")
            .arg(&refused));
        assert!(!ok && err.contains(needle), "{args:?}: {err}");
        assert!(!refused.exists());
    }
}

/// `lazysolid bench cuts` times every plane cut and the fracture as one row each, with the
/// voxels the caps need, the new ones synthesized, and the store's growth.
#[test]
fn bench_cuts_times_every_cut_and_fracture() {
    let out = tempfile::tempdir().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let exemplar = terra_square(dir.path(), 16);
    let bench = BenchRun::new(
        lazysolid()
            .args([
                "bench",
                "cuts",
                "--mesh",
                "elephant",
                "--voxel-res",
                "32",
                "--pieces",
                "4",
            ])
            .arg("--exemplar")
            .arg(&exemplar)
            .env("LAZYSOLID_CACHE_DIR", dir.path().join("cache")),
        out.path(),
        &[
            "32³ plane cut 1 normal [0.0, 1.0, 0.0]: new voxels",
            "32³ plane cut 4 normal [1.0, 1.0, 0.4]: wall ms",
            "32³ fracture 4 pieces: voxel versions synthesized",
            "32³ fracture 4 pieces: store MB after",
            "lazy request + insert (wall)",
            "thesis (2008 GPU): 8 ms",
        ],
    );
    assert!(bench.json()["rows"]
        .as_array()
        .is_some_and(|r| r.len() == 5));
}

/// `lazysolid bench glints`: per example size, build rows of the sparse table and the min–max
/// mip (CPU and device) and query rows of all three methods (the suite fails unless their
/// answers are identical), the memory table beside the paper's 0.44 %, the material's render
/// rows (pruned, explicit, conductor), and bad sizes and scenes refused.
#[test]
fn bench_glints_measures_range_queries_memory_and_render_time() {
    let out = tempfile::tempdir().unwrap();
    let scene = repo("scenes/glints.toml");
    let bench = BenchRun::new(
        lazysolid().args([
            "bench",
            "glints",
            "--scene",
            scene.to_str().unwrap(),
            "--render-res",
            "32x24",
            "--spp",
            "1",
            "--res",
            "32,128",
            "--exemplar",
            "leather",
            "--queries",
            "500",
            "--coverage",
            "5120",
            "--warmup",
            "0",
            "--runs",
            "1",
        ]),
        out.path(),
        &[
            "32² leather query",
            "128² generated query",
            "sparse table (gpu)",
            "min–max mip (cpu, 1 thread)",
            "brute force (gpu)",
            "Mquery/s",
            "5120²",
            "0.44 % Chair",
            "render glints.toml 32×24 1 spp",
            "glint (pruned)",
            "glint (explicit)",
            "against the explicit reference",
        ],
    );
    let json = bench.json();
    assert_eq!(json["rows"].as_array().map(Vec::len), Some(23));
    assert!(
        json["derived"]["render glints.toml 32×24 1 spp: pruned / conductor"]
            .as_f64()
            .is_some_and(|r| r > 1.0)
    );
    // 32²: levels 0..=3 (l = 8) of 32² entries, 8 bytes each.
    assert_eq!(
        json["derived"]["32² leather: sparse table bytes"].as_f64(),
        Some((4 * 32 * 32 * 8) as f64)
    );
    assert!(
        json["derived"]["128² generated against coverage 5120²: constant / explicit %"]
            .as_f64()
            .is_some_and(|r| r > 0.0 && r < 1.0)
    );
    for (res, needle) in [
        ("48", "power of two"),
        ("32x64", "square"),
        ("8", "16..=2048"),
    ] {
        let (ok, _, err) = run(lazysolid().args(["bench", "glints", "--res", res]));
        assert!(!ok && err.contains(needle), "--res {res}: {err}");
    }
    let plain = repo("scenes/default.toml");
    let (ok, _, err) = run(lazysolid().args([
        "bench",
        "glints",
        "--part",
        "render",
        "--scene",
        plain.to_str().unwrap(),
    ]));
    assert!(
        !ok && err.contains("default.toml") && err.contains("no kind = \"glint\" material"),
        "{err}"
    );
}

/// `lazysolid multiscale` and `lazysolid zoom` on a loop graph: the window and the frames are
/// written, and a bad graph fails with its file, line and field and leaves no output.
#[test]
fn multiscale_and_zoom_write_their_images_and_bad_graphs_fail_by_line() {
    let dir = tempfile::tempdir().unwrap();
    let graph = dir.path().join("g.toml");
    let text = "root = \"terra\"\n\n[[exemplar]]\nname = \"terra\"\nimage = \"terra\"\n\n\
                [[edge]]\nsource = \"terra\"\ndestination = \"terra\"\nr = 1\n";
    std::fs::write(&graph, text).unwrap();
    // GPU (with validation) and the CPU reference write the same image.
    let mut images = Vec::new();
    for extra in [&[][..], &["--cpu"][..]] {
        let out = dir.path().join(format!("out{}.png", images.len()));
        let (ok, stdout, err) = run(lazysolid()
            .arg("multiscale")
            .arg(&graph)
            .args(["--level", "8", "--res", "24x16", "--offset", "-5,3"])
            .args(extra)
            .arg("-o")
            .arg(&out)
            .env("LAZYSOLID_VALIDATION", "1"));
        assert!(ok, "{err}");
        assert!(
            stdout.contains("exemplar terra") && stdout.contains("100.0 %"),
            "{stdout}"
        );
        let image = image::open(&out).unwrap();
        assert_eq!((image.width(), image.height()), (24, 16));
        assert!(out.with_extension("exemplars.png").exists());
        images.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(images[0], images[1]);
    let zoom = dir.path().join("zoom");
    let (ok, _, err) = run(lazysolid()
        .arg("zoom")
        .arg(&graph)
        .args([
            "--from",
            "5",
            "--to",
            "6.5",
            "--frame-count",
            "3",
            "--res",
            "16x12",
        ])
        .arg("--out-dir")
        .arg(&zoom));
    assert!(ok, "{err}");
    for f in [
        "frame_0000.png",
        "frame_0001.png",
        "frame_0002.png",
        "zoom.gif",
    ] {
        assert!(zoom.join(f).exists(), "{f}");
    }
    // r at r_max (terra is 64², L = 6: r_max = 3), named by file, line and field.
    std::fs::write(&graph, text.replace("r = 1", "r = 3")).unwrap();
    let out = dir.path().join("bad.png");
    let (ok, _, err) = run(lazysolid()
        .arg("multiscale")
        .arg(&graph)
        .args(["--level", "3", "-o"])
        .arg(&out));
    assert!(!ok);
    assert!(err.contains("g.toml:10: edge #1.r: r = 3"), "{err}");
    assert!(!err.contains("panicked") && !out.exists(), "{err}");
}
