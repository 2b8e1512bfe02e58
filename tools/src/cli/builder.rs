//! `--builder`: where a perfect hash is constructed, for every subcommand that builds one.

use clap::ValueEnum;
use lazysolid_compute::hash::perfect::PerfectConstruction;

/// The perfect hash's construction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum Builder {
    /// The faster one on the device: the CPU build on a CPU driver (lavapipe), else the GPU's.
    #[default]
    Auto,
    /// The sequential greedy build on the host, then one upload.
    Cpu,
    /// The parallel construction in Vulkan compute.
    Gpu,
}

impl From<Builder> for PerfectConstruction {
    fn from(b: Builder) -> PerfectConstruction {
        match b {
            Builder::Auto => PerfectConstruction::Auto,
            Builder::Cpu => PerfectConstruction::Cpu,
            Builder::Gpu => PerfectConstruction::Gpu,
        }
    }
}
