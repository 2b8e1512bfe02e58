//! The build revision: `--version` reports the checkout's, and every bench result records it.

use crate::support::{lazysolid, repo, run, BenchRun};
use std::process::Command;

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
