//! `lazysolid bench prims`: the primitives' table, its CSV and JSON with one timestamp, and bad
//! arguments refused.

use crate::support::{lazysolid, run, BenchRun};

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
