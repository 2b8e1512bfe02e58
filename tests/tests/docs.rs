//! The documentation's walks through the code name real files: every repository path in
//! `docs/architecture.md` (a backticked path under a top-level folder of the workspace) exists,
//! so a move or a rename that leaves the walk behind fails here.

use std::path::Path;

/// Top-level folders a repository path in the docs starts with.
const ROOTS: [&str; 8] = [
    "compute/",
    "synth/",
    "renderer/",
    "tools/",
    "tests/",
    "glsl/",
    "docs/",
    "scripts/",
];

/// Every backticked span of `text` that looks like a repository path.
fn repository_paths(text: &str) -> Vec<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|span| ROOTS.iter().any(|r| span.starts_with(r)))
        .filter(|span| !span.contains(' '))
        .flat_map(expand)
        .collect()
}

/// `a/{b,c}/` names `a/b/` and `a/c/`; `a/b.rs`/`c.rs` stays one path.
fn expand(span: &str) -> Vec<String> {
    match (span.find('{'), span.find('}')) {
        (Some(open), Some(close)) if open < close => span[open + 1..close]
            .split(',')
            .map(|part| format!("{}{}{}", &span[..open], part, &span[close + 1..]))
            .collect(),
        _ => vec![span.to_string()],
    }
}

/// Whether `path` exists below `root`; a `*` in its file name matches any run of characters
/// (`lazy_*.comp` holds when one such file exists).
fn exists(root: &Path, path: &str) -> bool {
    let path = root.join(path.trim_end_matches('/'));
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let Some((head, tail)) = name.split_once('*') else {
        return path.exists();
    };
    std::fs::read_dir(path.parent().unwrap()).is_ok_and(|entries| {
        entries.flatten().any(|e| {
            let n = e.file_name().to_string_lossy().to_string();
            n.len() >= head.len() + tail.len() && n.starts_with(head) && n.ends_with(tail)
        })
    })
}

#[test]
fn every_path_the_architecture_walks_name_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let text = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let paths = repository_paths(&text);
    assert!(paths.len() >= 30, "only {} paths found", paths.len());
    let missing: Vec<&String> = paths.iter().filter(|p| !exists(&root, p)).collect();
    assert!(
        missing.is_empty(),
        "docs/architecture.md names missing paths: {missing:?}"
    );
}

#[test]
fn the_path_finder_sees_paths_and_expands_braces() {
    let text = "see `compute/src/{gpu,prims}/` and `tools/x.rs`, not `cargo test` or `src/a.rs`";
    assert_eq!(
        repository_paths(text),
        ["compute/src/gpu/", "compute/src/prims/", "tools/x.rs"]
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    assert!(exists(&root, "glsl/synth/solid/lazy_*.comp"));
    assert!(!exists(&root, "glsl/synth/solid/lazy_*.glsl"));
    assert!(!exists(&root, "compute/src/no_such_file.rs"));
}
