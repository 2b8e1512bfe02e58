//! Subcommands that are not benchmarks, and what every subcommand shares.

pub mod assets;
pub mod builder;
pub mod candidate_builder;
pub mod components;
pub mod device;
pub mod diff;
pub mod exit_status;
pub mod fit_mode;
pub mod fracture;
pub mod multiscale;
pub mod output;
pub mod renamed;
pub mod render;
pub mod resolution;
pub mod solid;
pub mod solid_render;
pub mod synth;
pub mod tuning;

use lazysolid_compute::gpu::{Gpu, GpuOptions, Validation, ValidationLog};
use std::cell::RefCell;
use std::sync::Arc;

/// Flags every subcommand accepts, and the validation logs of the devices it created.
pub struct GlobalArgs {
    pub device: Option<String>,
    pub verbose: bool,
    /// `--validation`: the layer on, as `LAZYSOLID_VALIDATION=1`.
    pub validation: bool,
    pub validation_logs: RefCell<Vec<Arc<ValidationLog>>>,
}

impl GlobalArgs {
    /// Creates the device the flags and environment ask for and, with `--verbose`, says which.
    pub fn gpu(&self) -> anyhow::Result<Gpu> {
        let mut options = GpuOptions::from_env();
        if self.device.is_some() {
            options.device = self.device.clone();
        }
        if self.validation {
            options.validation = Validation::Required("--validation is given".into());
        }
        let gpu = Gpu::new(&options)?;
        if gpu.validation_enabled() {
            self.validation_logs.borrow_mut().push(gpu.validation_log());
        }
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

impl GlobalArgs {
    /// After every device is gone (leaks are reported at destruction): the number of validation
    /// errors, each printed.
    pub fn report_validation(&self) -> u32 {
        let mut errors = 0;
        for log in self.validation_logs.borrow().iter() {
            errors += log.errors();
            for m in log.messages() {
                eprintln!("validation: {m}");
            }
        }
        if !self.validation_logs.borrow().is_empty() && (self.verbose || errors > 0) {
            eprintln!("Vulkan validation layer: {errors} error(s)");
        }
        errors
    }
}
