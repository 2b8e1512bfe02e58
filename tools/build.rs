//! Records the project's own revision at build time as `LAZYSOLID_REVISION`: what the bench
//! result files and `lazysolid --version` report, independent of the folder a command runs in.
//!
//! The revision is `git rev-parse --short=12 HEAD` of the checkout the crate is built from,
//! with `-dirty` when tracked files differ from it; `unknown` when the sources are not in a git
//! checkout (or git is absent). `LAZYSOLID_REVISION` set in the build's environment wins, for
//! builds from a source archive that know their revision.

use std::path::Path;
use std::process::Command;

fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn main() {
    // Read at run time: a build script binary reused from another checkout's target folder
    // must still ask the checkout being built.
    let manifest_dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
    let dir = Path::new(&manifest_dir);
    println!("cargo:rerun-if-env-changed=LAZYSOLID_REVISION");
    let revision = match std::env::var("LAZYSOLID_REVISION") {
        Ok(r) if !r.trim().is_empty() => r.trim().to_string(),
        _ => revision_from_git(dir),
    };
    println!("cargo:rustc-env=LAZYSOLID_REVISION={revision}");
}

fn revision_from_git(dir: &Path) -> String {
    let Some(rev) = git(dir, &["rev-parse", "--short=12", "HEAD"]) else {
        return "unknown".into();
    };
    // Rebuild when HEAD moves, the branch it names moves, or the index changes (commits and
    // staging), and when any source of the workspace changes (the dirty flag).
    for path in ["HEAD", "index"] {
        if let Some(p) = git(dir, &["rev-parse", "--git-path", path]) {
            println!("cargo:rerun-if-changed={}", dir.join(p).display());
        }
    }
    if let Some(head_ref) = git(dir, &["symbolic-ref", "-q", "HEAD"]) {
        if let Some(p) = git(dir, &["rev-parse", "--git-path", &head_ref]) {
            println!("cargo:rerun-if-changed={}", dir.join(p).display());
        }
    }
    let root = dir.join("..");
    for source in [
        "compute",
        "renderer",
        "tools",
        "glsl",
        "Cargo.toml",
        "Cargo.lock",
    ] {
        println!("cargo:rerun-if-changed={}", root.join(source).display());
    }
    let dirty =
        git(dir, &["status", "--porcelain", "--untracked-files=no"]).is_some_and(|s| !s.is_empty());
    if dirty {
        format!("{rev}-dirty")
    } else {
        rev
    }
}
