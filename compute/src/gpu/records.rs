//! Buffers of records that hold device addresses (a store's parameters, an environment's
//! tables), borrowing every buffer those addresses point into.

use super::address::DeviceAddress;
use super::buffer::{BufferArg, GpuBuffer};
use super::context::Gpu;
use super::error::GpuResult;
use super::keep_alive::KeepAlive;
use super::push::{align_up, PushValue};

/// A device buffer of records laid out as GLSL's scalar layout lays out an array of them,
/// holding the memory of every buffer the records' [`DeviceAddress`] fields point into: a
/// record on the device cannot point into freed memory, however long it is kept, and its
/// owner needs no other field to keep those buffers.
///
/// [`DeviceAddress`]: super::DeviceAddress
pub struct DeviceRecords {
    buffer: GpuBuffer<u8>,
    _targets: KeepAlive,
}

impl DeviceRecords {
    /// Uploads `records` (at least one: a binding cannot be empty).
    ///
    /// # Errors
    /// Allocation and upload errors.
    pub fn new<R: PushValue>(gpu: &Gpu, name: &str, records: &[R]) -> GpuResult<Self> {
        let stride = align_up(R::SIZE, R::ALIGN) as usize;
        let mut bytes = vec![0u8; stride * records.len()];
        let mut targets = KeepAlive::default();
        for (i, r) in records.iter().enumerate() {
            r.write(&mut bytes[i * stride..]);
            r.keep_alive(&mut targets);
        }
        Ok(DeviceRecords {
            buffer: GpuBuffer::from_slice(gpu, name, &bytes)?,
            _targets: targets,
        })
    }

    /// The records as a dispatch argument.
    pub fn arg(&self) -> BufferArg<'_> {
        self.buffer.arg()
    }

    /// The address of the first record, for kernels that reach the records through
    /// `GL_EXT_buffer_reference`.
    pub fn address(&self) -> DeviceAddress<'_> {
        self.buffer.address()
    }
}
