//! Every file lazysolid reads from its users, fuzzed: valid seed files mutated by a few edits
//! (`mutate.rs`) and handed to the reader, which must return a value or an error that names
//! the file, within a time limit and a memory bound, and never panic (`oracle.rs`). One module
//! per format. Each also replays its regression cases, the inputs that once broke a reader,
//! kept as files in `tests/fuzz-regressions/<format>/`.
//!
//! CI runs [`oracle::cases`] cases per seed file; `LAZYSOLID_FUZZ_CASES=N` runs more (the long
//! mode, `docs/testing.md`).

mod caches;
mod graphs;
mod images;
mod maps;
mod meshes;
mod mutate;
mod nrrd;
mod oracle;
mod scenes;

use std::path::{Path, PathBuf};

/// The repository's root.
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The regression inputs of `format`, sorted (none when the folder is absent).
fn regressions(format: &str) -> Vec<PathBuf> {
    let folder = repo().join("tests/fuzz-regressions").join(format);
    let mut files: Vec<PathBuf> = match std::fs::read_dir(&folder) {
        Ok(entries) => entries.map(|e| e.unwrap().path()).collect(),
        Err(_) => Vec::new(),
    };
    files.retain(|f| f.is_file());
    files.sort();
    files
}

/// Writes one case's bytes to `name` in a fresh temporary folder, which lives as long as the
/// returned guard: the readers take paths, and their errors must quote them.
fn write_case(name: &str, bytes: &[u8]) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("the case's file");
    (dir, path)
}

/// A seed file: a name (with the extension its reader dispatches on) and its bytes.
struct Seed {
    name: String,
    bytes: Vec<u8>,
}

impl Seed {
    fn file(path: &Path) -> Seed {
        Seed {
            name: path.file_name().unwrap().to_string_lossy().into_owned(),
            bytes: std::fs::read(path).unwrap_or_else(|e| panic!("seed {}: {e}", path.display())),
        }
    }
}
