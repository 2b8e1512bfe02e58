//! The Vulkan core: device and its required features, validation, buffers, the kernel cache,
//! submission and timing.
//!
//! ```
//! use lazysolid_compute::gpu::{Gpu, GpuBuffer, GpuOptions};
//! let gpu = Gpu::new(&GpuOptions::from_env())?;
//! let data = GpuBuffer::from_slice(&gpu, "data", &[1u32, 2, 3])?;
//! assert_eq!(data.read()?, vec![1, 2, 3]);
//! # Ok::<(), lazysolid_compute::gpu::GpuError>(())
//! ```

mod address;
mod buffer;
mod commands;
mod context;
mod device_info;
mod error;
mod features;
mod keep_alive;
mod kernel;
mod layer_lock;
mod memory;
mod meter;
mod push;
mod records;
mod submissions;
mod validation;

pub use address::DeviceAddress;
pub use buffer::{BufferArg, GpuBuffer};
pub use commands::{elapsed_ns, Recorder, MAX_TIMESTAMPS};
pub use context::{Gpu, GpuOptions, Validation, WeakGpu, DEVICE_ENV, VALIDATION_ENV};
pub use device_info::{DeviceInfo, DESIGN_SHARED_MEMORY, DESIGN_WORKGROUP_INVOCATIONS};
pub use error::{GpuError, GpuResult};
pub use features::{check_features, Feature, REQUIRED_FEATURES};
pub use keep_alive::KeepAlive;
pub use kernel::{BindingDef, BindingKind, Kernel, KernelDef, WORKGROUP_SIZE_ID};
pub use memory::{MemoryMode, MEMORY_ENV};
pub use meter::MemoryUse;
pub use push::{
    align_up, check_fields, check_push_block, host_fields, push_bytes, HostField, PushBlock,
    PushFieldDef, PushRegistration, PushValue,
};
pub use records::DeviceRecords;
pub use submissions::{KernelTime, Submissions};
pub use validation::{ValidationLog, VALIDATION_LAYER};
