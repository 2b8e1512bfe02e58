//! The baseline left out: a build without the tools' `peers` feature (the main job's, which
//! never runs `bench synth` and saves the peer's compilation) refuses the comparison by name
//! before any work.

use lazysolid_synth::Exemplar;

/// Why `bench synth` cannot run in this build.
const ABSENT: &str = "bench synth compares with the texture-synthesis crate, which this build \
                      left out: build lazysolid-tools with its default features (feature `peers`)";

/// A run's result: none is made in this build ([`synthesize`] refuses).
pub struct Generated(());

/// What a run yields (never, in this build).
pub struct Output {
    /// RGB pixels, row-major.
    pub rgb: Vec<[u8; 3]>,
    /// Exemplar coordinates per pixel.
    pub coords: Vec<u32>,
}

/// Refuses: the baseline is not built in.
pub fn check_available() -> anyhow::Result<()> {
    anyhow::bail!(ABSENT)
}

/// The settings the baseline would run with.
pub fn settings(threads: usize) -> String {
    format!("texture-synthesis not built in (max_thread_count {threads} unused)")
}

/// Refuses: the baseline is not built in.
pub fn synthesize(_: &Exemplar, _: u32, _: u64, _: usize) -> anyhow::Result<Generated> {
    anyhow::bail!(ABSENT)
}

/// Refuses: no run exists to read.
pub fn output(_: Generated, _: &Exemplar, _: u32) -> anyhow::Result<Output> {
    anyhow::bail!(ABSENT)
}
