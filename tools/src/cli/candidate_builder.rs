//! `--candidates`: where the solid candidates are computed, for every subcommand that
//! computes them.

use clap::ValueEnum;
use lazysolid_synth::solid::CandidateBuilder;

/// The solid candidates' builder; both give the same candidates, bit for bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Candidates {
    /// The faster one on the device: the pruned host search on a CPU driver (lavapipe), else
    /// the GPU kernels.
    #[default]
    Auto,
    /// The pruned exact searches on the host.
    Host,
    /// The brute-force kernels in Vulkan compute.
    Gpu,
}

impl From<Candidates> for CandidateBuilder {
    fn from(c: Candidates) -> CandidateBuilder {
        match c {
            Candidates::Auto => CandidateBuilder::Auto,
            Candidates::Host => CandidateBuilder::Host,
            Candidates::Gpu => CandidateBuilder::Gpu,
        }
    }
}
