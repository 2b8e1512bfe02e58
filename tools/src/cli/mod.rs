//! Subcommands that are not benchmarks, and what every subcommand shares.

pub mod device;

use lazysolid_compute::gpu::{Gpu, GpuOptions};

/// Flags every subcommand accepts.
pub struct GlobalArgs {
    pub device: Option<String>,
    pub verbose: bool,
}

impl GlobalArgs {
    /// Creates the device the flags and environment ask for and, with `--verbose`, says which.
    pub fn gpu(&self) -> anyhow::Result<Gpu> {
        let mut options = GpuOptions::from_env();
        if self.device.is_some() {
            options.device = self.device.clone();
        }
        let gpu = Gpu::new(&options)?;
        if self.verbose {
            let i = gpu.info();
            eprintln!(
                "device {}: {} ({}, {}), validation {}",
                i.index,
                i.name,
                i.device_type,
                i.driver,
                if gpu.validation_enabled() {
                    "on"
                } else {
                    "off"
                }
            );
        }
        Ok(gpu)
    }
}
