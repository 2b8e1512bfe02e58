//! The device features and extensions lazysolid creates its device with: one table that the
//! device choice checks (so a missing one is reported by name, with the device's name, before
//! `vkCreateDevice`) and that the device creation enables (so nothing is enabled unchecked).

use super::error::{GpuError, GpuResult};
use ash::vk;
use std::ffi::CStr;

/// A capability of a physical device that lazysolid's kernels or core rely on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// Vulkan 1.3 on the device: the 1.2 and 1.3 feature structures are chained at creation.
    Vulkan13,
    /// `shaderInt64`: 64-bit keys, device addresses and the integer marble.
    ShaderInt64,
    /// `bufferDeviceAddress`: kernels address buffers through `GL_EXT_buffer_reference`.
    BufferDeviceAddress,
    /// `scalarBlockLayout`: push blocks and records use the scalar layout.
    ScalarBlockLayout,
    /// `shaderBufferInt64Atomics`: the 64-bit hash cells are inserted with 64-bit atomics.
    ShaderBufferInt64Atomics,
    /// `maintenance4`: `LocalSizeId` workgroup sizes and `maxBufferSize`.
    Maintenance4,
    /// `VK_KHR_push_descriptor`: every dispatch pushes its descriptors.
    PushDescriptor,
    /// Subgroup basic, arithmetic, ballot and shuffle operations in compute shaders.
    SubgroupOps,
    /// Timestamp queries on a compute queue: every benchmark's GPU times.
    ComputeTimestamps,
}

/// Every feature the device is created with, in the order they are reported.
pub const REQUIRED_FEATURES: &[Feature] = &[
    Feature::Vulkan13,
    Feature::ShaderInt64,
    Feature::BufferDeviceAddress,
    Feature::ScalarBlockLayout,
    Feature::ShaderBufferInt64Atomics,
    Feature::Maintenance4,
    Feature::PushDescriptor,
    Feature::SubgroupOps,
    Feature::ComputeTimestamps,
];

impl Feature {
    /// The name the Vulkan specification (and `vulkaninfo`) uses.
    pub fn name(self) -> &'static str {
        match self {
            Feature::Vulkan13 => "Vulkan 1.3",
            Feature::ShaderInt64 => "shaderInt64",
            Feature::BufferDeviceAddress => "bufferDeviceAddress",
            Feature::ScalarBlockLayout => "scalarBlockLayout",
            Feature::ShaderBufferInt64Atomics => "shaderBufferInt64Atomics",
            Feature::Maintenance4 => "maintenance4",
            Feature::PushDescriptor => "VK_KHR_push_descriptor",
            Feature::SubgroupOps => "subgroup arithmetic/ballot/shuffle in compute",
            Feature::ComputeTimestamps => "timestamp queries on a compute queue",
        }
    }
}

impl std::fmt::Display for Feature {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Checks that `supported` holds every feature of `required`.
///
/// # Errors
/// [`GpuError::MissingFeature`] naming the device and every missing feature.
pub fn check_features(device: &str, supported: &[Feature], required: &[Feature]) -> GpuResult<()> {
    let missing: Vec<&str> = required
        .iter()
        .filter(|f| !supported.contains(f))
        .map(|f| f.name())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    Err(GpuError::MissingFeature {
        device: device.to_string(),
        missing: missing.join(", "),
    })
}

/// The feature structures of the Vulkan API, as queried from a device or passed to
/// `vkCreateDevice`.
#[derive(Default)]
pub(crate) struct FeatureStructs {
    pub core: vk::PhysicalDeviceFeatures,
    pub v12: vk::PhysicalDeviceVulkan12Features<'static>,
    pub v13: vk::PhysicalDeviceVulkan13Features<'static>,
}

/// What a physical device offers, as far as [`Feature`] goes.
pub(crate) struct DeviceCapabilities<'a> {
    pub api_version: u32,
    pub features: &'a FeatureStructs,
    pub extensions: &'a [vk::ExtensionProperties],
    pub subgroup: &'a vk::PhysicalDeviceSubgroupProperties<'a>,
    pub compute_timestamps: bool,
}

impl DeviceCapabilities<'_> {
    /// The features of the table the device supports.
    pub fn supported(&self) -> Vec<Feature> {
        let has_ext = |name: &CStr| {
            self.extensions
                .iter()
                .any(|e| e.extension_name_as_c_str() == Ok(name))
        };
        let needed_ops = vk::SubgroupFeatureFlags::BASIC
            | vk::SubgroupFeatureFlags::ARITHMETIC
            | vk::SubgroupFeatureFlags::BALLOT
            | vk::SubgroupFeatureFlags::SHUFFLE;
        let f = self.features;
        let v13 = vk::api_version_major(self.api_version) > 1
            || vk::api_version_minor(self.api_version) >= 3;
        let on = |b: vk::Bool32| b == vk::TRUE;
        REQUIRED_FEATURES
            .iter()
            .copied()
            .filter(|feature| match feature {
                Feature::Vulkan13 => v13,
                Feature::ShaderInt64 => on(f.core.shader_int64),
                Feature::BufferDeviceAddress => on(f.v12.buffer_device_address),
                Feature::ScalarBlockLayout => on(f.v12.scalar_block_layout),
                Feature::ShaderBufferInt64Atomics => on(f.v12.shader_buffer_int64_atomics),
                Feature::Maintenance4 => v13 && on(f.v13.maintenance4),
                Feature::PushDescriptor => has_ext(ash::khr::push_descriptor::NAME),
                Feature::SubgroupOps => {
                    self.subgroup
                        .supported_stages
                        .contains(vk::ShaderStageFlags::COMPUTE)
                        && self.subgroup.supported_operations.contains(needed_ops)
                }
                Feature::ComputeTimestamps => self.compute_timestamps,
            })
            .collect()
    }
}

/// The feature structures and extensions that enable `features` at device creation.
pub(crate) fn enabled(features: &[Feature]) -> (FeatureStructs, Vec<&'static CStr>) {
    let mut s = FeatureStructs::default();
    let mut extensions = Vec::new();
    for feature in features {
        match feature {
            // Properties of the device or its queues, not switches.
            Feature::Vulkan13 | Feature::SubgroupOps | Feature::ComputeTimestamps => {}
            Feature::ShaderInt64 => s.core.shader_int64 = vk::TRUE,
            Feature::BufferDeviceAddress => s.v12.buffer_device_address = vk::TRUE,
            Feature::ScalarBlockLayout => s.v12.scalar_block_layout = vk::TRUE,
            Feature::ShaderBufferInt64Atomics => s.v12.shader_buffer_int64_atomics = vk::TRUE,
            Feature::Maintenance4 => s.v13.maintenance4 = vk::TRUE,
            Feature::PushDescriptor => extensions.push(ash::khr::push_descriptor::NAME),
        }
    }
    (s, extensions)
}
