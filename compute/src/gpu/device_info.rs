//! What lazysolid needs to know about a physical device, read once and printed by `lazysolid device`.

use super::error::GpuResult;
use super::features::{
    check_features, DeviceCapabilities, Feature, FeatureStructs, REQUIRED_FEATURES,
};
use ash::vk;
use std::ffi::CStr;

/// The `maxComputeSharedMemorySize` every kernel is designed to fit: lavapipe's, and the
/// smallest among common GPUs (NVIDIA offers 48 KiB, AMD and Intel 64 KiB; Vulkan guarantees
/// only 16 KiB). Kernels check their need against the device and name the limit when over it.
pub const DESIGN_SHARED_MEMORY: u32 = 32 * 1024;
/// The largest workgroup any kernel is designed to use: common GPUs allow 1024 invocations,
/// Vulkan guarantees only 128; lazysolid's kernels use 64–256.
pub const DESIGN_WORKGROUP_INVOCATIONS: u32 = 256;

/// Properties and limits of one physical device that lazysolid's kernels depend on.
#[derive(Clone, Debug)]
pub struct DeviceInfo {
    /// Index in the loader's enumeration order (what `--device INDEX` refers to).
    pub index: usize,
    /// `deviceName`, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub name: String,
    /// Discrete, integrated, virtual or CPU.
    pub device_type: String,
    /// Driver name and info string, e.g. `llvmpipe / Mesa 22.3.6 (LLVM 15.0.6)`.
    pub driver: String,
    /// Vulkan API version the device supports, as `major.minor.patch`.
    pub api_version: String,
    /// `maxStorageBufferRange`: the largest range one storage-buffer binding may cover.
    pub max_storage_buffer_range: u64,
    /// `minStorageBufferOffsetAlignment`.
    pub min_storage_buffer_offset_alignment: u64,
    /// `maxMemoryAllocationSize`.
    pub max_memory_allocation_size: u64,
    /// `maxBufferSize` (Vulkan 1.3 / maintenance4), or `u64::MAX` where unreported.
    pub max_buffer_size: u64,
    /// Size of the largest device-local heap.
    pub heap_size: u64,
    /// Whether that heap is host-visible (uploads are mapped writes, no staging).
    pub heap_host_visible: bool,
    /// Subgroup size.
    pub subgroup_size: u32,
    /// `maxComputeSharedMemorySize`.
    pub max_shared_memory: u32,
    /// `maxComputeWorkGroupCount[0]`.
    pub max_workgroup_count: u32,
    /// `maxComputeWorkGroupInvocations`.
    pub max_workgroup_invocations: u32,
    /// The features of [`REQUIRED_FEATURES`] the device supports.
    pub features: Vec<Feature>,
    /// `timestampPeriod`: nanoseconds per timestamp tick (1 on lavapipe and NVIDIA; tens of
    /// nanoseconds on many AMD and Intel GPUs).
    pub timestamp_period_ns: f32,
    /// `timestampValidBits` of the queue family lazysolid submits to (the first compute family
    /// with timestamps), 0 when none: the bits of a timestamp that count, 64 on lavapipe and
    /// 36–64 on GPUs. Differences are taken modulo `2^bits`.
    pub timestamp_valid_bits: u32,
}

impl DeviceInfo {
    /// Whether the device is a CPU implementation (lavapipe): work that runs faster as native
    /// code than as a kernel on the same cores chooses the host there.
    pub fn is_cpu(&self) -> bool {
        self.device_type == "cpu"
    }

    /// Preference when no device is named: discrete, integrated, virtual, then CPU.
    pub(crate) fn preference(&self) -> u32 {
        match self.device_type.as_str() {
            "discrete GPU" => 0,
            "integrated GPU" => 1,
            "virtual GPU" => 2,
            "cpu" => 4,
            _ => 3,
        }
    }

    /// Whether the device supports `feature`.
    pub fn has(&self, feature: Feature) -> bool {
        self.features.contains(&feature)
    }

    /// The names of the required features the device lacks, empty when it is usable.
    pub fn missing_requirements(&self) -> Vec<&'static str> {
        REQUIRED_FEATURES
            .iter()
            .filter(|f| !self.has(**f))
            .map(|f| f.name())
            .collect()
    }

    /// Checks the device against [`REQUIRED_FEATURES`].
    ///
    /// # Errors
    /// [`GpuError::MissingFeature`](super::GpuError::MissingFeature) with the device's name and every missing feature.
    pub fn check_requirements(&self) -> GpuResult<()> {
        check_features(&self.name, &self.features, REQUIRED_FEATURES)
    }

    pub(crate) fn read(
        instance: &ash::Instance,
        physical: vk::PhysicalDevice,
        index: usize,
    ) -> Self {
        let mut driver = vk::PhysicalDeviceDriverProperties::default();
        let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
        let mut maint4 = vk::PhysicalDeviceMaintenance4Properties::default();
        let mut props2 = vk::PhysicalDeviceProperties2::default()
            .push_next(&mut driver)
            .push_next(&mut subgroup)
            .push_next(&mut maint4);
        unsafe { instance.get_physical_device_properties2(physical, &mut props2) };
        let props = props2.properties;
        let features = read_features(instance, physical, props.api_version);
        let memory = unsafe { instance.get_physical_device_memory_properties(physical) };
        let heaps = &memory.memory_heaps[..memory.memory_heap_count as usize];
        let types = &memory.memory_types[..memory.memory_type_count as usize];
        let (heap_index, heap) = heaps
            .iter()
            .enumerate()
            .filter(|(_, h)| h.flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL))
            .max_by_key(|(_, h)| h.size)
            .or_else(|| heaps.iter().enumerate().max_by_key(|(_, h)| h.size))
            .expect("a device has at least one heap");
        let heap_host_visible = types.iter().any(|t| {
            t.heap_index as usize == heap_index
                && t.property_flags.contains(
                    vk::MemoryPropertyFlags::HOST_VISIBLE | vk::MemoryPropertyFlags::HOST_COHERENT,
                )
        });
        let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
        // The same family `create_device` picks.
        let timestamp_valid_bits = families
            .iter()
            .find(|f| f.queue_flags.contains(vk::QueueFlags::COMPUTE) && f.timestamp_valid_bits > 0)
            .map_or(0, |f| f.timestamp_valid_bits);
        let timestamps = timestamp_valid_bits > 0;
        let extensions =
            unsafe { instance.enumerate_device_extension_properties(physical) }.unwrap_or_default();
        let supported = DeviceCapabilities {
            api_version: props.api_version,
            features: &features,
            extensions: &extensions,
            subgroup: &subgroup,
            compute_timestamps: timestamps,
        }
        .supported();
        let text = |raw: &[std::ffi::c_char]| {
            unsafe { CStr::from_ptr(raw.as_ptr()) }
                .to_string_lossy()
                .into_owned()
        };
        let v = props.api_version;
        DeviceInfo {
            index,
            name: text(&props.device_name),
            device_type: match props.device_type {
                vk::PhysicalDeviceType::DISCRETE_GPU => "discrete GPU",
                vk::PhysicalDeviceType::INTEGRATED_GPU => "integrated GPU",
                vk::PhysicalDeviceType::VIRTUAL_GPU => "virtual GPU",
                vk::PhysicalDeviceType::CPU => "cpu",
                _ => "other",
            }
            .to_string(),
            driver: format!(
                "{} / {}",
                text(&driver.driver_name),
                text(&driver.driver_info)
            ),
            api_version: format!(
                "{}.{}.{}",
                vk::api_version_major(v),
                vk::api_version_minor(v),
                vk::api_version_patch(v)
            ),
            max_storage_buffer_range: props.limits.max_storage_buffer_range as u64,
            min_storage_buffer_offset_alignment: props.limits.min_storage_buffer_offset_alignment,
            max_memory_allocation_size: {
                let mut m3 = vk::PhysicalDeviceMaintenance3Properties::default();
                let mut p = vk::PhysicalDeviceProperties2::default().push_next(&mut m3);
                unsafe { instance.get_physical_device_properties2(physical, &mut p) };
                m3.max_memory_allocation_size
            },
            max_buffer_size: if maint4.max_buffer_size == 0 {
                u64::MAX
            } else {
                maint4.max_buffer_size
            },
            heap_size: heap.size,
            heap_host_visible,
            subgroup_size: subgroup.subgroup_size,
            max_shared_memory: props.limits.max_compute_shared_memory_size,
            max_workgroup_count: props.limits.max_compute_work_group_count[0],
            max_workgroup_invocations: props.limits.max_compute_work_group_invocations,
            features: supported,
            timestamp_period_ns: props.limits.timestamp_period,
            timestamp_valid_bits,
        }
    }
}

/// The device's core, Vulkan 1.2 and (on a 1.3 device) Vulkan 1.3 feature structures.
pub(crate) fn read_features(
    instance: &ash::Instance,
    physical: vk::PhysicalDevice,
    api_version: u32,
) -> FeatureStructs {
    let mut f = FeatureStructs::default();
    let mut features2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f.v12);
    if vk::api_version_minor(api_version) >= 3 || vk::api_version_major(api_version) > 1 {
        features2 = features2.push_next(&mut f.v13);
    }
    unsafe { instance.get_physical_device_features2(physical, &mut features2) };
    let core = features2.features;
    // The chain pointed into this frame; the structures travel on without it.
    f.core = core;
    f.v12.p_next = std::ptr::null_mut();
    f.v13.p_next = std::ptr::null_mut();
    f
}
