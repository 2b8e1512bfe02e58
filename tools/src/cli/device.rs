//! `lazysolid device`: what each Vulkan device offers that lazysolid relies on.

use lazysolid_compute::gpu::{
    DeviceInfo, Gpu, GpuOptions, MemoryMode, MEMORY_ENV, REQUIRED_FEATURES,
};

fn mib(bytes: u64) -> String {
    if bytes == u64::MAX {
        "unreported".into()
    } else {
        format!("{:.0} MiB", bytes as f64 / (1024.0 * 1024.0))
    }
}

fn yes(b: bool) -> &'static str {
    if b {
        "yes"
    } else {
        "NO"
    }
}

/// Prints every device and marks the one lazysolid would use.
pub fn run(wanted: Option<&str>) -> anyhow::Result<()> {
    // A bad switch is an error of its own, not "no usable device".
    let memory = MemoryMode::from_env()?;
    let devices = Gpu::list_devices()?;
    // Which device would be chosen: resolve it the way every other subcommand does, without
    // validation (listing must work where the layer is absent).
    let mut options = GpuOptions::from_env();
    options.validation = Default::default();
    if let Some(w) = wanted {
        options.device = Some(w.to_string());
    }
    let chosen = Gpu::new(&options).map(|g| g.info().index);
    for d in &devices {
        print_device(d, chosen.as_ref().ok() == Some(&d.index));
    }
    if let Err(e) = chosen {
        anyhow::bail!("no usable device: {e}");
    }
    println!(
        "memory mode: {} ({MEMORY_ENV}){}",
        memory.name(),
        match memory {
            MemoryMode::Auto => "",
            MemoryMode::DeviceLocal => ": every upload and readback through staging",
        }
    );
    Ok(())
}

fn print_device(d: &DeviceInfo, chosen: bool) {
    println!(
        "device {}: {}{}",
        d.index,
        d.name,
        if chosen {
            "   <- used by lazysolid"
        } else {
            ""
        }
    );
    let missing = d.missing_requirements();
    let mut rows: Vec<(&str, String)> = vec![
        ("type", d.device_type.clone()),
        ("driver", d.driver.clone()),
        ("Vulkan API", d.api_version.clone()),
        ("maxStorageBufferRange", mib(d.max_storage_buffer_range)),
        (
            "device heap",
            format!(
                "{}{}",
                mib(d.heap_size),
                if d.heap_host_visible {
                    " (host-visible: uploads are mapped writes)"
                } else {
                    ""
                }
            ),
        ),
        ("maxMemoryAllocationSize", mib(d.max_memory_allocation_size)),
        ("maxBufferSize", mib(d.max_buffer_size)),
        ("subgroup size", d.subgroup_size.to_string()),
        ("timestamp period", format!("{} ns", d.timestamp_period_ns)),
        ("timestamp valid bits", d.timestamp_valid_bits.to_string()),
        (
            "compute shared memory",
            format!("{} KiB", d.max_shared_memory / 1024),
        ),
        (
            "max workgroup invocations",
            d.max_workgroup_invocations.to_string(),
        ),
        ("max workgroup count (x)", d.max_workgroup_count.to_string()),
        (
            "usable by lazysolid",
            if missing.is_empty() {
                "yes".to_string()
            } else {
                format!("NO, lacks {}", missing.join(", "))
            },
        ),
    ];
    // Every feature the device is created with, as the device choice checks them, before
    // the verdict.
    let verdict = rows.len() - 1;
    rows.splice(
        verdict..verdict,
        REQUIRED_FEATURES
            .iter()
            .map(|f| (f.name(), yes(d.has(*f)).to_string())),
    );
    for (k, v) in rows {
        println!("  {k:<36} {v}");
    }
}
