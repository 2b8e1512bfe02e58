//! Device addresses that borrow their buffer, so that an address cannot outlive the memory it
//! points into: a push block or record holding one is tied to the buffer by the borrow checker.

use super::buffer::{BufferMemory, GpuBuffer};
use super::error::{GpuError, GpuResult};
use super::keep_alive::KeepAlive;
use bytemuck::Pod;
use std::sync::Arc;

/// The device address of an element of a [`GpuBuffer`], for kernels that reach memory through
/// `GL_EXT_buffer_reference` (a `uint64_t` in GLSL). It borrows the buffer for `'a`, so every
/// push block and record that carries it borrows the buffer too: dropping or replacing the
/// buffer while such a value is alive does not compile. Whatever takes the value further —
/// a dispatch until its submission completes, [`DeviceRecords`](super::DeviceRecords) for as
/// long as they live — holds the buffer's memory through it.
///
/// ```no_run
/// use lazysolid_compute::gpu::{Gpu, GpuBuffer, GpuOptions};
/// let gpu = Gpu::new(&GpuOptions::from_env())?;
/// let buffer = GpuBuffer::<u32>::new(&gpu, "data", 4)?;
/// let address = buffer.address();
/// println!("{address:?}");
/// drop(buffer);
/// # Ok::<(), lazysolid_compute::gpu::GpuError>(())
/// ```
///
/// The same with the buffer dropped while the address is still used does not compile:
///
/// ```compile_fail
/// use lazysolid_compute::gpu::{Gpu, GpuBuffer, GpuOptions};
/// let gpu = Gpu::new(&GpuOptions::from_env())?;
/// let buffer = GpuBuffer::<u32>::new(&gpu, "data", 4)?;
/// let address = buffer.address();
/// drop(buffer);
/// println!("{address:?}");
/// # Ok::<(), lazysolid_compute::gpu::GpuError>(())
/// ```
#[derive(Clone, Copy)]
pub struct DeviceAddress<'a> {
    raw: u64,
    memory: Option<&'a Arc<BufferMemory>>,
}

impl PartialEq for DeviceAddress<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.raw == other.raw
    }
}

impl Eq for DeviceAddress<'_> {}

impl std::fmt::Debug for DeviceAddress<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "DeviceAddress({:#x})", self.raw)
    }
}

impl DeviceAddress<'static> {
    /// Address 0, which no buffer has: for record fields a kernel does not read (the store of
    /// another kind in a union-like record, absent normals).
    pub const NULL: DeviceAddress<'static> = DeviceAddress {
        raw: 0,
        memory: None,
    };
}

impl Default for DeviceAddress<'_> {
    fn default() -> Self {
        DeviceAddress::NULL
    }
}

impl DeviceAddress<'_> {
    /// The address as a number, for messages and comparisons (there is no way back).
    pub fn raw(self) -> u64 {
        self.raw
    }

    /// True for [`DeviceAddress::NULL`].
    pub fn is_null(self) -> bool {
        self.raw == 0
    }

    /// Makes `keep` hold the buffer's memory.
    pub fn keep_alive(self, keep: &mut KeepAlive) {
        if let Some(m) = self.memory {
            keep.hold(m);
        }
    }
}

impl<T: Pod> GpuBuffer<T> {
    /// Device address of the first element, borrowing the buffer (see [`DeviceAddress`]).
    pub fn address(&self) -> DeviceAddress<'_> {
        DeviceAddress {
            raw: self.raw_address(),
            memory: Some(self.memory()),
        }
    }

    /// Device address of element `first` (`first == len()` is the end, as for slices).
    ///
    /// # Errors
    /// `first` past the end of the buffer.
    pub fn address_at(&self, first: usize) -> GpuResult<DeviceAddress<'_>> {
        if first > self.len() {
            return Err(GpuError::InvalidArgument(format!(
                "buffer {:?}: address of element {first} is past its {} elements",
                self.name(),
                self.len()
            )));
        }
        Ok(DeviceAddress {
            raw: self.raw_address() + (first * size_of::<T>()) as u64,
            memory: Some(self.memory()),
        })
    }
}
