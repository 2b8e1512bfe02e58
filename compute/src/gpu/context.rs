//! Instance, device choice, validation messenger, queue and allocator: the one owner of them all.

use super::device_info::DeviceInfo;
use super::error::{GpuError, GpuResult, VkContext};
use super::features::{enabled, Feature, REQUIRED_FEATURES};
use super::kernel::KernelCache;
use super::layer_lock;
use super::memory::MemoryMode;
use super::validation::{messenger_callback, ValidationLog, VALIDATION_LAYER};
use ash::vk;
use gpu_allocator::vulkan::{Allocator, AllocatorCreateDesc};
use std::ffi::{CStr, CString};
use std::mem::ManuallyDrop;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, Weak};

/// Environment variable naming the device (`NAME` substring or `INDEX`), like `--device`.
pub const DEVICE_ENV: &str = "LAZYSOLID_DEVICE";
/// Environment variable that turns the validation layer on when set to `1`.
pub const VALIDATION_ENV: &str = "LAZYSOLID_VALIDATION";

/// Whether the Khronos validation layer is loaded.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Validation {
    /// No layer (the default outside tests: it slows API calls).
    #[default]
    Off,
    /// The layer must be present; the string says why (it appears in the error when missing).
    Required(String),
}

/// How to create a [`Gpu`].
#[derive(Clone, Debug, Default)]
pub struct GpuOptions {
    /// Device to use: a case-insensitive substring of its name, or its index. `None` picks a real
    /// GPU when one is present and lavapipe otherwise.
    pub device: Option<String>,
    /// Validation layer on or off.
    pub validation: Validation,
    /// How buffers reach host data. `None` reads `LAZYSOLID_MEMORY` when the device is
    /// created, so every way of creating a device honours the switch.
    pub memory: Option<MemoryMode>,
}

impl GpuOptions {
    /// Options from `LAZYSOLID_DEVICE` and `LAZYSOLID_VALIDATION`.
    pub fn from_env() -> Self {
        let device = std::env::var(DEVICE_ENV)
            .ok()
            .filter(|s| !s.trim().is_empty());
        let validation = match std::env::var(VALIDATION_ENV).as_deref() {
            Ok("1") => Validation::Required(format!("{VALIDATION_ENV}=1 is set")),
            _ => Validation::Off,
        };
        GpuOptions {
            device,
            validation,
            memory: None,
        }
    }

    /// Options for tests: the environment's device choice, validation always required.
    pub fn for_tests() -> Self {
        GpuOptions {
            validation: Validation::Required("tests always run with validation".into()),
            ..Self::from_env()
        }
    }
}

/// A Vulkan device ready for compute work, with its kernel cache. Cloning is cheap and shares
/// both; the device lives until the last clone and the last buffer or kernel made from it are
/// gone.
#[derive(Clone)]
pub struct Gpu {
    pub(crate) inner: Arc<GpuInner>,
    pub(crate) kernels: Arc<KernelCache>,
}

pub(crate) struct GpuInner {
    _entry: ash::Entry,
    instance: ash::Instance,
    messenger: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT)>,
    pub(crate) debug_device: Option<ash::ext::debug_utils::Device>,
    pub(crate) device: ash::Device,
    pub(crate) push_descriptor: ash::khr::push_descriptor::Device,
    pub(crate) queue: Mutex<vk::Queue>,
    pub(crate) queue_family: u32,
    pub(crate) allocator: ManuallyDrop<Mutex<Allocator>>,
    pub(crate) info: DeviceInfo,
    pub(crate) memory: MemoryMode,
    /// Uploads and readbacks that went through a staging buffer.
    pub(crate) staging_copies: AtomicU64,
    /// Bytes of buffer memory allocated, live and peak.
    pub(crate) meter: super::meter::Meter,
    pub(crate) submissions: super::submissions::SubmissionMeter,
    validation_log: Arc<ValidationLog>,
}

impl Gpu {
    /// Creates the device described by `options`.
    ///
    /// # Errors
    /// No or no matching device, a missing feature or validation layer, an unknown
    /// `LAZYSOLID_MEMORY` value, Vulkan and allocator failures.
    pub fn new(options: &GpuOptions) -> GpuResult<Gpu> {
        let memory = match options.memory {
            Some(m) => m,
            None => MemoryMode::from_env()?,
        };
        let entry =
            unsafe { ash::Entry::load() }.map_err(|e| GpuError::LoaderMissing(e.to_string()))?;
        let validation = match &options.validation {
            Validation::Off => false,
            Validation::Required(reason) => {
                let layers = unsafe { entry.enumerate_instance_layer_properties() }
                    .vk("vkEnumerateInstanceLayerProperties", "instance")?;
                if !layers
                    .iter()
                    .any(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER))
                {
                    return Err(GpuError::ValidationLayerMissing {
                        reason: reason.clone(),
                    });
                }
                true
            }
        };
        // Held until the device exists (see `layer_lock`).
        let _layer = layer_lock::exclusive(validation);
        let instance = create_instance(&entry, validation)?;
        let validation_log = Arc::new(ValidationLog::default());
        let messenger = if validation {
            let loader = ash::ext::debug_utils::Instance::new(&entry, &instance);
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(
                    vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
                        | vk::DebugUtilsMessageSeverityFlagsEXT::WARNING,
                )
                .message_type(
                    vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE
                        | vk::DebugUtilsMessageTypeFlagsEXT::GENERAL,
                )
                .pfn_user_callback(Some(messenger_callback))
                .user_data(Arc::as_ptr(&validation_log) as *mut std::ffi::c_void);
            match unsafe { loader.create_debug_utils_messenger(&info, None) } {
                Ok(m) => Some((loader, m)),
                Err(result) => {
                    unsafe { instance.destroy_instance(None) };
                    return Err(GpuError::Vulkan {
                        call: "vkCreateDebugUtilsMessengerEXT",
                        object: "validation messenger".into(),
                        result,
                    });
                }
            }
        } else {
            None
        };
        // From here on, a failure must tear down what exists; a partial GpuInner cannot, so the
        // device creation is done in a helper and cleaned up here.
        match create_device(&instance, options) {
            Ok((physical, info, device, queue_family)) => {
                let queue = unsafe { device.get_device_queue(queue_family, 0) };
                let allocator = Allocator::new(&AllocatorCreateDesc {
                    instance: instance.clone(),
                    device: device.clone(),
                    physical_device: physical,
                    debug_settings: Default::default(),
                    buffer_device_address: true,
                    allocation_sizes: Default::default(),
                });
                let allocator = match allocator {
                    Ok(a) => a,
                    Err(e) => {
                        unsafe {
                            device.destroy_device(None);
                            if let Some((loader, m)) = &messenger {
                                loader.destroy_debug_utils_messenger(*m, None);
                            }
                            instance.destroy_instance(None);
                        }
                        return Err(GpuError::Allocation {
                            object: "allocator".into(),
                            bytes: 0,
                            source: e,
                        });
                    }
                };
                let push_descriptor = ash::khr::push_descriptor::Device::new(&instance, &device);
                let debug_device =
                    validation.then(|| ash::ext::debug_utils::Device::new(&instance, &device));
                log::info!(
                    "Vulkan device {} ({}, {}), validation {}, memory {}",
                    info.name,
                    info.device_type,
                    info.driver,
                    if validation { "on" } else { "off" },
                    memory.name()
                );
                Ok(Gpu {
                    kernels: Arc::default(),
                    inner: Arc::new(GpuInner {
                        _entry: entry,
                        instance,
                        messenger,
                        debug_device,
                        device,
                        push_descriptor,
                        queue: Mutex::new(queue),
                        queue_family,
                        allocator: ManuallyDrop::new(Mutex::new(allocator)),
                        info,
                        memory,
                        staging_copies: AtomicU64::new(0),
                        meter: super::meter::Meter::default(),
                        submissions: super::submissions::SubmissionMeter::default(),
                        validation_log,
                    }),
                })
            }
            Err(e) => {
                unsafe {
                    if let Some((loader, m)) = &messenger {
                        loader.destroy_debug_utils_messenger(*m, None);
                    }
                    instance.destroy_instance(None);
                }
                Err(e)
            }
        }
    }

    /// Every Vulkan device the loader sees, with the limits lazysolid relies on.
    pub fn list_devices() -> GpuResult<Vec<DeviceInfo>> {
        let entry =
            unsafe { ash::Entry::load() }.map_err(|e| GpuError::LoaderMissing(e.to_string()))?;
        let instance = create_instance(&entry, false)?;
        let result = enumerate(&instance).map(|v| v.into_iter().map(|(_, info)| info).collect());
        unsafe { instance.destroy_instance(None) };
        result
    }

    /// The chosen device's properties and limits.
    pub fn info(&self) -> &DeviceInfo {
        &self.inner.info
    }

    /// How this device's buffers reach host data (see [`MemoryMode`]).
    pub fn memory_mode(&self) -> MemoryMode {
        self.inner.memory
    }

    /// How many uploads and readbacks have gone through a staging buffer so far: every one in
    /// [`MemoryMode::DeviceLocal`], none on a host-visible heap otherwise.
    pub fn staging_copies(&self) -> u64 {
        self.inner.staging_copies.load(Ordering::Relaxed)
    }

    /// What the validation layer reported; it stays readable after the device is destroyed, when
    /// the layer reports leaked objects.
    pub fn validation_log(&self) -> Arc<ValidationLog> {
        self.inner.validation_log.clone()
    }

    /// Whether the validation layer is loaded.
    pub fn validation_enabled(&self) -> bool {
        self.inner.messenger.is_some()
    }

    /// A weak handle that tells whether the device has been destroyed (all owners dropped).
    pub fn downgrade(&self) -> WeakGpu {
        WeakGpu(Arc::downgrade(&self.inner))
    }

    /// Runs `call` on the raw `ash` device, for the occasional call the core does not wrap.
    /// The call runs under the validation layer's lock (see `layer_lock`), so a device created
    /// or destroyed on another thread meanwhile cannot crash it.
    pub fn with_device<R>(&self, call: impl FnOnce(&ash::Device) -> R) -> R {
        let _layer = self.inner.layer();
        call(&self.inner.device)
    }
}

/// See [`Gpu::downgrade`].
pub struct WeakGpu(Weak<GpuInner>);

impl WeakGpu {
    /// True once every owner of the device is gone and the device has been destroyed.
    pub fn is_destroyed(&self) -> bool {
        self.0.strong_count() == 0
    }
}

impl GpuInner {
    /// Holds the validation layer's map shared for a call of this device (see `layer_lock`).
    pub(crate) fn layer(&self) -> layer_lock::SharedHold {
        layer_lock::shared(self.messenger.is_some())
    }

    /// Gives a Vulkan object a debug name so validation messages say which buffer or kernel.
    pub(crate) fn set_name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(debug) = &self.debug_device {
            if let Ok(name) = CString::new(name) {
                let info = vk::DebugUtilsObjectNameInfoEXT::default()
                    .object_handle(handle)
                    .object_name(&name);
                let _layer = self.layer();
                let _ = unsafe { debug.set_debug_utils_object_name(&info) };
            }
        }
    }
}

impl Drop for GpuInner {
    fn drop(&mut self) {
        let _layer = layer_lock::exclusive(self.messenger.is_some());
        unsafe {
            let _ = self.device.device_wait_idle();
            ManuallyDrop::drop(&mut self.allocator);
            self.device.destroy_device(None);
            if let Some((loader, m)) = &self.messenger {
                loader.destroy_debug_utils_messenger(*m, None);
            }
            self.instance.destroy_instance(None);
        }
    }
}

fn create_instance(entry: &ash::Entry, validation: bool) -> GpuResult<ash::Instance> {
    let app = vk::ApplicationInfo::default()
        .application_name(c"lazysolid")
        .engine_name(c"lazysolid")
        .api_version(vk::API_VERSION_1_3);
    let layers = if validation {
        vec![VALIDATION_LAYER.as_ptr()]
    } else {
        vec![]
    };
    let extensions = if validation {
        vec![ash::ext::debug_utils::NAME.as_ptr()]
    } else {
        vec![]
    };
    let info = vk::InstanceCreateInfo::default()
        .application_info(&app)
        .enabled_layer_names(&layers)
        .enabled_extension_names(&extensions);
    match unsafe { entry.create_instance(&info, None) } {
        Ok(i) => Ok(i),
        Err(vk::Result::ERROR_INCOMPATIBLE_DRIVER) => Err(GpuError::NoDevice),
        Err(result) => Err(GpuError::Vulkan {
            call: "vkCreateInstance",
            object: "instance".into(),
            result,
        }),
    }
}

fn enumerate(instance: &ash::Instance) -> GpuResult<Vec<(vk::PhysicalDevice, DeviceInfo)>> {
    let physicals = match unsafe { instance.enumerate_physical_devices() } {
        Ok(p) => p,
        Err(vk::Result::ERROR_INITIALIZATION_FAILED) => return Err(GpuError::NoDevice),
        Err(result) => {
            return Err(GpuError::Vulkan {
                call: "vkEnumeratePhysicalDevices",
                object: "instance".into(),
                result,
            })
        }
    };
    if physicals.is_empty() {
        return Err(GpuError::NoDevice);
    }
    Ok(physicals
        .into_iter()
        .enumerate()
        .map(|(i, p)| (p, DeviceInfo::read(instance, p, i)))
        .collect())
}

fn choose(
    devices: Vec<(vk::PhysicalDevice, DeviceInfo)>,
    wanted: Option<&str>,
) -> GpuResult<(vk::PhysicalDevice, DeviceInfo)> {
    let available = || {
        devices
            .iter()
            .map(|(_, d)| format!("{}: {}", d.index, d.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match wanted.map(str::trim) {
        Some(w) if !w.is_empty() => {
            let found = if let Ok(index) = w.parse::<usize>() {
                devices.iter().find(|(_, d)| d.index == index)
            } else {
                let lower = w.to_lowercase();
                devices
                    .iter()
                    .find(|(_, d)| d.name.to_lowercase().contains(&lower))
            };
            match found {
                Some(d) => Ok(d.clone()),
                None => Err(GpuError::DeviceNotFound {
                    wanted: w.to_string(),
                    available: available(),
                }),
            }
        }
        _ => {
            // Prefer real GPUs that meet the requirements; fall back to the CPU driver.
            let usable = devices
                .iter()
                .filter(|(_, d)| d.missing_requirements().is_empty())
                .min_by_key(|(_, d)| (d.preference(), d.index));
            Ok(usable
                .or_else(|| devices.iter().find(|(_, d)| d.is_cpu()))
                .unwrap_or(&devices[0])
                .clone())
        }
    }
}

fn create_device(
    instance: &ash::Instance,
    options: &GpuOptions,
) -> GpuResult<(vk::PhysicalDevice, DeviceInfo, ash::Device, u32)> {
    let (physical, info) = choose(enumerate(instance)?, options.device.as_deref())?;
    info.check_requirements()?;
    let families = unsafe { instance.get_physical_device_queue_family_properties(physical) };
    let queue_family = families
        .iter()
        .position(|f| f.queue_flags.contains(vk::QueueFlags::COMPUTE) && f.timestamp_valid_bits > 0)
        .ok_or_else(|| GpuError::MissingFeature {
            device: info.name.clone(),
            missing: Feature::ComputeTimestamps.name().into(),
        })? as u32;
    let priorities = [1.0f32];
    let queues = [vk::DeviceQueueCreateInfo::default()
        .queue_family_index(queue_family)
        .queue_priorities(&priorities)];
    // Exactly the checked features: nothing the device choice did not see is enabled.
    let (mut features, extensions) = enabled(REQUIRED_FEATURES);
    let extensions: Vec<_> = extensions.iter().map(|e| e.as_ptr()).collect();
    let info_ci = vk::DeviceCreateInfo::default()
        .queue_create_infos(&queues)
        .enabled_extension_names(&extensions)
        .enabled_features(&features.core)
        .push_next(&mut features.v12)
        .push_next(&mut features.v13);
    let device = unsafe { instance.create_device(physical, &info_ci, None) }
        .vk("vkCreateDevice", info.name.clone())?;
    Ok((physical, info, device, queue_family))
}

/// Name of a C string slice for messages.
#[allow(dead_code)]
pub(crate) fn cstr(s: &CStr) -> String {
    s.to_string_lossy().into_owned()
}
