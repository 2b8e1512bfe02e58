//! What every reader must do with any input: return, within a time limit, either a value or
//! an error whose message names the file, without panicking and without allocating more than
//! a bound stated per reader. A broken rule fails the case, which proptest then shrinks to
//! the smallest input that still breaks it. The time limit is proptest's per-case `timeout`,
//! which runs the cases in a child process so that a hang is caught too. The memory is
//! counted by `lazysolid_compute::host_memory`'s allocator, installed below.

use lazysolid_compute::host_memory::{self, CountingAllocator};
use proptest::test_runner::{Config, RngSeed, TestCaseError};
use std::fmt::Display;

/// Counts every allocation of this test binary: how a reader's allocation from a size field
/// is measured.
#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// Milliseconds one case may take (debug build, two loaded cores; a case takes milliseconds).
pub const CASE_TIMEOUT_MS: u32 = 20_000;

/// Cases per seed file in CI; `LAZYSOLID_FUZZ_CASES` sets another count (the long mode).
const DEFAULT_CASES: u32 = 48;

/// The cases each seed file gets: [`DEFAULT_CASES`] unless `LAZYSOLID_FUZZ_CASES` says.
pub fn cases() -> u32 {
    match std::env::var("LAZYSOLID_FUZZ_CASES") {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("LAZYSOLID_FUZZ_CASES={v} is not a whole number")),
        Err(_) => DEFAULT_CASES,
    }
}

/// The seed of the inputs CI draws: the same cases on every run, so a submission never fails
/// on a case no earlier run met.
const DEFAULT_SEED: u64 = 0x6c61_7a79_736f_6c64;

/// The random seed of the drawn inputs: [`DEFAULT_SEED`] unless `LAZYSOLID_FUZZ_SEED` gives a
/// number, or `random` for a new seed on every run (the long mode's exploration).
fn rng_seed() -> RngSeed {
    match std::env::var("LAZYSOLID_FUZZ_SEED").as_deref() {
        Err(_) => RngSeed::Fixed(DEFAULT_SEED),
        Ok("random") => RngSeed::Random,
        Ok(v) => RngSeed::Fixed(v.parse().unwrap_or_else(|_| {
            panic!("LAZYSOLID_FUZZ_SEED={v} is neither a whole number nor `random`")
        })),
    }
}

/// proptest's configuration for a fuzz test over `seeds` seed files: [`cases`] cases per
/// seed drawn from [`rng_seed`], each in a child process under [`CASE_TIMEOUT_MS`], failures
/// persisted beside the sources (`proptest-regressions/`).
pub fn config_for(seeds: usize) -> Config {
    Config {
        cases: cases() * seeds as u32,
        timeout: CASE_TIMEOUT_MS,
        rng_seed: rng_seed(),
        ..Config::default()
    }
}

/// One input of a fuzz test: its format (the folder of its regression cases), the file name
/// its errors must quote, and its bytes (kept when the case fails).
pub struct Case<'a> {
    /// `images`, `maps`, `meshes`, `nrrd`, `scenes`, `graphs` or `caches`.
    pub format: &'a str,
    /// The file's name, which an error message must contain (empty: no file to name).
    pub name: &'a str,
    /// The input.
    pub bytes: &'a [u8],
}

/// Runs `read` on `case` and checks the oracle: no panic, an `Err` names the file, and the
/// most memory held at once during the call stays within `max_bytes`. A failing input is
/// written to `target/fuzz-failures/<format>/` (the path is in the failure), ready to be
/// moved into `tests/fuzz-regressions/<format>/`.
///
/// # Errors
/// A [`TestCaseError`] saying which rule the input broke.
pub fn check<T, E: Display>(
    case: &Case,
    max_bytes: usize,
    read: impl FnOnce() -> Result<T, E>,
) -> Result<(), TestCaseError> {
    let before = host_memory::mark();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(read));
    let peak = host_memory::peak().saturating_sub(before) as usize;
    let broken = match &result {
        Err(panic) => Some(format!(
            "panicked: {}",
            panic
                .downcast_ref::<String>()
                .map(String::as_str)
                .or_else(|| panic.downcast_ref::<&str>().copied())
                .unwrap_or("(no message)")
        )),
        Ok(_) if peak > max_bytes => Some(format!(
            "held {peak} bytes at once, above the bound of {max_bytes}"
        )),
        Ok(Err(e)) if !e.to_string().contains(case.name) => {
            Some(format!("the error does not name {}: {e}", case.name))
        }
        Ok(_) => None,
    };
    match broken {
        None => Ok(()),
        Some(why) => Err(TestCaseError::fail(format!(
            "{why} (input kept as {})",
            keep(case)
        ))),
    }
}

/// Writes a failing input under `target/fuzz-failures/<format>/`, named by its checksum and
/// its file name; returns where (or why it could not).
fn keep(case: &Case) -> String {
    let folder = crate::repo().join("target/fuzz-failures").join(case.format);
    let name = if case.name.is_empty() {
        "payload.bin"
    } else {
        case.name
    };
    let path = folder.join(format!("{:08x}-{name}", crc32fast::hash(case.bytes)));
    match std::fs::create_dir_all(&folder).and_then(|()| std::fs::write(&path, case.bytes)) {
        Ok(()) => path.display().to_string(),
        Err(e) => format!("nowhere: {e}"),
    }
}

/// The bound on memory for a reader whose allocation follows the input: `per_input_byte`
/// times the input's length, plus `fixed`.
pub fn bound(input_len: usize, per_input_byte: usize, fixed: usize) -> usize {
    fixed + per_input_byte * input_len
}

/// Mebibytes.
pub const MIB: usize = 1 << 20;

#[test]
fn the_oracle_catches_what_it_checks() {
    let case = Case {
        format: "oracle-self-test",
        name: "a.off",
        bytes: b"OFF",
    };
    assert!(check(&case, MIB, || Ok::<_, String>(())).is_ok());
    let named = check(&case, MIB, || Err::<(), _>("/tmp/a.off: line 3: bad count"));
    assert!(named.is_ok());
    let failure = |r: Result<(), TestCaseError>| r.unwrap_err().to_string();
    let unnamed = failure(check(&case, MIB, || Err::<(), _>("bad count")));
    assert!(unnamed.contains("does not name a.off"), "{unnamed}");
    assert!(
        unnamed.contains("fuzz-failures/oracle-self-test/"),
        "{unnamed}"
    );
    let greedy = failure(check(&case, MIB, || {
        let held = vec![1u8; 4 * MIB];
        Err::<(), _>(format!("a.off: {}", held.len()))
    }));
    assert!(greedy.contains("above the bound"), "{greedy}");
    let panicky = failure(check(&case, MIB, || -> Result<(), String> {
        panic!("index out of bounds")
    }));
    assert!(
        panicky.contains("panicked: index out of bounds"),
        "{panicky}"
    );
    let kept = crate::repo().join("target/fuzz-failures/oracle-self-test");
    std::fs::remove_dir_all(kept).unwrap();
}
