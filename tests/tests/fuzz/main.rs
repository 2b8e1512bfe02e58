//! Every file lazysolid reads from its users, fuzzed: valid seed files mutated by a few edits
//! (`mutate.rs`) and handed to the reader, which must return a value or an error that names
//! the file, within a time limit and a memory bound, and never panic (`oracle.rs`). One module
//! per format. Each also replays its regression cases, the inputs that once broke a reader,
//! kept as files in `tests/fuzz-regressions/<format>/`.
//!
//! CI runs [`oracle::cases`] cases per seed file; `LAZYSOLID_FUZZ_CASES=N` runs more (the long
//! mode, `docs/testing.md`).

/// A format's two fixed tests: its seeds are read, and its regression inputs replayed
/// (`FileFormat::seeds_are_read`, `FileFormat::replay_regressions`).
macro_rules! fixed_tests {
    ($format:expr, $seeds:expr) => {
        #[test]
        fn the_seeds_are_read() {
            $format.seeds_are_read($seeds);
        }

        #[test]
        fn regression_cases() {
            $format.replay_regressions();
        }
    };
}

mod caches;
mod graphs;
mod images;
mod maps;
mod meshes;
mod mutate;
mod nrrd;
mod oracle;
mod scenes;

use proptest::test_runner::TestCaseError;
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

/// A format whose reader takes a file path: its regression folder, its reader and its memory
/// bound for an input of a given length. The three tests every such format has go through it.
struct FileFormat {
    /// The folder of its regression inputs, and the `format` of its cases.
    name: &'static str,
    /// The reader; only its success or its error matters.
    read: fn(&Path) -> Result<(), String>,
    /// The most memory the reader may hold for an input of this many bytes.
    bound: fn(usize) -> usize,
}

impl FileFormat {
    /// Every seed is read without error (a mutation engine that starts from broken seeds
    /// checks little).
    fn seeds_are_read(&self, seeds: &[Seed]) {
        for s in seeds {
            let (_dir, path) = write_case(&s.name, &s.bytes);
            (self.read)(&path).unwrap_or_else(|e| panic!("seed {}: {e}", s.name));
        }
    }

    /// Every regression input of the format passes the oracle.
    fn replay_regressions(&self) {
        for file in regressions(self.name) {
            let name = file.file_name().unwrap().to_string_lossy().into_owned();
            let bytes = std::fs::read(&file).unwrap();
            self.case(&name, &bytes).unwrap();
        }
    }

    /// Writes `bytes` as a file named `name` and checks the reader on it.
    fn case(&self, name: &str, bytes: &[u8]) -> Result<(), TestCaseError> {
        let (_dir, path) = write_case(name, bytes);
        let case = oracle::Case {
            format: self.name,
            name,
            bytes,
        };
        oracle::check(&case, (self.bound)(bytes.len()), || (self.read)(&path))
    }
}
