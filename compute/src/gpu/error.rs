//! The one error type of the Vulkan core: every failure names the object, kernel or limit involved.

use ash::vk;

/// Errors raised by the Vulkan core and the kernels built on it.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// The Vulkan loader library could not be opened.
    #[error("cannot load the Vulkan loader (libvulkan.so.1): {0}; install the Debian package libvulkan1")]
    LoaderMissing(String),
    /// The loader found no physical device at all.
    #[error("no Vulkan device found; for the CPU driver lavapipe install the Debian package mesa-vulkan-drivers (ICD manifests are read from /usr/share/vulkan/icd.d, or from VK_ICD_FILENAMES when set)")]
    NoDevice,
    /// `--device` / `LAZYSOLID_DEVICE` matched none of the devices present.
    #[error("no Vulkan device matches {wanted:?}; available devices: {available}")]
    DeviceNotFound {
        /// What the user asked for.
        wanted: String,
        /// `index: name` of every device present.
        available: String,
    },
    /// The Khronos validation layer was requested but is not installed.
    #[error("the Vulkan validation layer VK_LAYER_KHRONOS_validation is not installed (Debian package vulkan-validationlayers; layer manifests are read from /usr/share/vulkan/explicit_layer.d or VK_LAYER_PATH); it is required because {reason}")]
    ValidationLayerMissing {
        /// Why validation was on (a test, or `LAZYSOLID_VALIDATION=1`).
        reason: String,
    },
    /// The chosen device lacks a feature or extension lazysolid relies on.
    #[error("device {device:?} lacks {missing}, which lazysolid requires")]
    MissingFeature {
        /// Device name.
        device: String,
        /// The feature or extension.
        missing: String,
    },
    /// A request exceeds a device limit and cannot be split.
    #[error("{what}: {requested} bytes exceeds the device limit {limit_name} = {limit} bytes")]
    OverLimit {
        /// The object the request was for.
        what: String,
        /// Requested size in bytes.
        requested: u64,
        /// The Vulkan limit's name, as in the specification.
        limit_name: &'static str,
        /// The limit's value.
        limit: u64,
    },
    /// A Vulkan call failed.
    #[error("{call} failed for {object}: {result}")]
    Vulkan {
        /// The Vulkan entry point.
        call: &'static str,
        /// The object or kernel it was called for.
        object: String,
        /// The result code.
        result: vk::Result,
    },
    /// gpu-allocator refused an allocation.
    #[error("allocating {bytes} bytes for {object}: {source}")]
    Allocation {
        /// The buffer's name.
        object: String,
        /// Requested size.
        bytes: u64,
        /// The allocator's error.
        source: gpu_allocator::AllocationError,
    },
    /// A kernel was dispatched with bindings or push constants that do not match its GLSL.
    #[error("kernel {kernel}: {problem}")]
    KernelInterface {
        /// The kernel's GLSL file.
        kernel: &'static str,
        /// What does not match.
        problem: String,
    },
    /// A GPU-side bounded loop ran out of iterations or a kernel reported a failure counter.
    #[error("kernel {kernel} reported failure: {problem}")]
    KernelFailure {
        /// The kernel's GLSL file.
        kernel: &'static str,
        /// What went wrong.
        problem: String,
    },
    /// An argument is outside what an operation supports.
    #[error("{0}")]
    InvalidArgument(String),
    /// A setting (an environment variable or option) holds a value it does not accept.
    #[error("{setting}={value:?} is not accepted; expected one of: {expected}")]
    BadSetting {
        /// The variable or option, e.g. `LAZYSOLID_MEMORY`.
        setting: String,
        /// The value found.
        value: String,
        /// The accepted values, comma-separated.
        expected: String,
    },
}

/// Result type of the Vulkan core.
pub type GpuResult<T> = Result<T, GpuError>;

/// Attaches the Vulkan call and object name to an `ash` result.
pub(crate) trait VkContext<T> {
    fn vk(self, call: &'static str, object: impl Into<String>) -> GpuResult<T>;
}

impl<T> VkContext<T> for Result<T, vk::Result> {
    fn vk(self, call: &'static str, object: impl Into<String>) -> GpuResult<T> {
        self.map_err(|result| GpuError::Vulkan {
            call,
            object: object.into(),
            result,
        })
    }
}
