//! Typed GPU buffers: one owner per `VkBuffer`, whose memory is freed once neither the buffer
//! nor work recorded with it nor records pointing into it hold it.

use super::context::{Gpu, GpuInner};
use super::error::{GpuError, GpuResult, VkContext};
use super::memory::MemoryMode;
use ash::vk;
use bytemuck::Pod;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;
use std::marker::PhantomData;
use std::sync::atomic::Ordering;
use std::sync::Arc;

/// A buffer of `len` elements of `T`, usable as a storage buffer, through its device address,
/// and as a transfer source and destination.
///
/// Uploads and readbacks are mapped copies when the memory is host-visible and coherent (always
/// on lavapipe, whose one heap is host memory) and go through a staging buffer otherwise, or
/// always under [`MemoryMode::DeviceLocal`](super::MemoryMode) (`LAZYSOLID_MEMORY=device-local`).
/// The mapping never leaves this type: nothing else writes or reads a buffer's memory directly.
pub struct GpuBuffer<T: Pod> {
    memory: Arc<BufferMemory>,
    len: usize,
    physical_bytes: u64,
    address: u64,
    name: String,
    _element: PhantomData<T>,
}

/// The `VkBuffer` and memory of a [`GpuBuffer`], freed when the last holder lets go: the
/// buffer itself, a [`Recorder`](super::Recorder) whose recorded work uses it, or a
/// [`DeviceRecords`](super::DeviceRecords) that points into it.
pub(crate) struct BufferMemory {
    gpu: Arc<GpuInner>,
    raw: vk::Buffer,
    allocation: Option<Allocation>,
}

impl Drop for BufferMemory {
    fn drop(&mut self) {
        let _layer = self.gpu.layer();
        if let Some(a) = self.allocation.take() {
            self.gpu.meter.sub(a.size());
            let _ = self.gpu.allocator.lock().unwrap().free(a);
        }
        unsafe { self.gpu.device.destroy_buffer(self.raw, None) };
    }
}

/// A buffer as seen by a dispatch: handle, size and name, with the element type erased.
#[derive(Clone, Copy)]
pub struct BufferArg<'a> {
    pub(crate) memory: &'a Arc<BufferMemory>,
    pub(crate) raw: vk::Buffer,
    pub(crate) offset: u64,
    pub(crate) bytes: u64,
    pub(crate) name: &'a str,
}

impl<T: Pod> GpuBuffer<T> {
    /// A buffer of `len` elements whose contents are unspecified until written.
    ///
    /// # Errors
    /// [`GpuError::OverLimit`] when the size exceeds `maxBufferSize`, `maxMemoryAllocationSize`
    /// or the device heap; allocation and Vulkan errors otherwise.
    pub fn new(gpu: &Gpu, name: impl Into<String>, len: usize) -> GpuResult<Self> {
        let name = name.into();
        let inner = gpu.inner.clone();
        let info = &inner.info;
        let requested = (len as u64)
            .checked_mul(size_of::<T>() as u64)
            .ok_or_else(|| {
                GpuError::InvalidArgument(format!("{name}: {len} elements overflow a 64-bit size"))
            })?;
        for (limit_name, limit) in [
            ("maxBufferSize", info.max_buffer_size),
            ("maxMemoryAllocationSize", info.max_memory_allocation_size),
            ("device heap size", info.heap_size),
        ] {
            if requested > limit {
                return Err(GpuError::OverLimit {
                    what: format!("buffer {name:?}"),
                    requested,
                    limit_name,
                    limit,
                });
            }
        }
        // Vulkan forbids empty buffers; an empty one still owns a minimal allocation. Sizes are
        // padded to 16 bytes so kernels may read the last, partial uvec4 of a binding.
        let bytes = requested.max(16).next_multiple_of(16);
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::UNIFORM_BUFFER
            | vk::BufferUsageFlags::TRANSFER_SRC
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::SHADER_DEVICE_ADDRESS
            | vk::BufferUsageFlags::INDIRECT_BUFFER;
        let create = vk::BufferCreateInfo::default()
            .size(bytes)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        let layer = inner.layer();
        let raw = unsafe { inner.device.create_buffer(&create, None) }
            .vk("vkCreateBuffer", name.clone())?;
        let requirements = unsafe { inner.device.get_buffer_memory_requirements(raw) };
        let allocation = inner
            .allocator
            .lock()
            .unwrap()
            .allocate(&AllocationCreateDesc {
                name: &name,
                requirements,
                location: MemoryLocation::GpuOnly,
                linear: true,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            });
        let allocation = match allocation {
            Ok(a) => a,
            Err(source) => {
                unsafe { inner.device.destroy_buffer(raw, None) };
                return Err(GpuError::Allocation {
                    object: name,
                    bytes,
                    source,
                });
            }
        };
        if let Err(result) = unsafe {
            inner
                .device
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        } {
            let _ = inner.allocator.lock().unwrap().free(allocation);
            unsafe { inner.device.destroy_buffer(raw, None) };
            return Err(GpuError::Vulkan {
                call: "vkBindBufferMemory",
                object: name,
                result,
            });
        }
        inner.meter.add(allocation.size());
        let address = unsafe {
            inner
                .device
                .get_buffer_device_address(&vk::BufferDeviceAddressInfo::default().buffer(raw))
        };
        inner.set_name(raw, &name);
        drop(layer);
        Ok(GpuBuffer {
            memory: Arc::new(BufferMemory {
                gpu: inner,
                raw,
                allocation: Some(allocation),
            }),
            len,
            physical_bytes: bytes,
            address,
            name,
            _element: PhantomData,
        })
    }

    /// A buffer holding a copy of `data`.
    pub fn from_slice(gpu: &Gpu, name: impl Into<String>, data: &[T]) -> GpuResult<Self> {
        let mut buffer = Self::new(gpu, name, data.len())?;
        buffer.write(0, data)?;
        Ok(buffer)
    }

    /// A buffer of `len` zeroed elements.
    pub fn zeroed(gpu: &Gpu, name: impl Into<String>, len: usize) -> GpuResult<Self> {
        let buffer = Self::new(gpu, name, len)?;
        gpu.submit(|rec| {
            rec.fill(&buffer, 0);
            Ok(())
        })?;
        Ok(buffer)
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the buffer holds no element.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Size of the elements in bytes (an empty buffer reports 0).
    pub fn bytes(&self) -> u64 {
        (self.len * size_of::<T>()) as u64
    }

    /// The number behind [`GpuBuffer::address`]; only `DeviceAddress` hands it out, with a
    /// borrow of the buffer.
    pub(super) fn raw_address(&self) -> u64 {
        self.address
    }

    /// The debug name given at creation.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The raw handle, for calls the core does not wrap.
    pub fn raw(&self) -> vk::Buffer {
        self.memory.raw
    }

    /// The shared memory, for holders that must keep it alive (recorded work, records).
    pub(crate) fn memory(&self) -> &Arc<BufferMemory> {
        &self.memory
    }

    /// This buffer as a dispatch argument.
    pub fn arg(&self) -> BufferArg<'_> {
        BufferArg {
            memory: &self.memory,
            raw: self.memory.raw,
            offset: 0,
            bytes: self
                .bytes()
                .next_multiple_of(16)
                .clamp(16, self.physical_bytes),
            name: &self.name,
        }
    }

    /// Elements `first .. first + count` as a dispatch argument: how data larger than
    /// `maxStorageBufferRange` is bound piece by piece. The byte offset must be a multiple of
    /// `minStorageBufferOffsetAlignment`; the range is padded to whole uvec4 (see `new`).
    ///
    /// # Errors
    /// An empty range, a range outside the buffer, or a misaligned offset.
    pub fn arg_range(&self, first: usize, count: usize) -> GpuResult<BufferArg<'_>> {
        self.check_range(first, count)?;
        if count == 0 {
            return Err(GpuError::InvalidArgument(format!(
                "buffer {:?}: an empty range cannot be bound",
                self.name
            )));
        }
        let offset = (first * size_of::<T>()) as u64;
        let align = self
            .memory
            .gpu
            .info
            .min_storage_buffer_offset_alignment
            .max(1);
        if offset % align != 0 {
            return Err(GpuError::InvalidArgument(format!(
                "buffer {:?}: binding offset {offset} bytes is not a multiple of minStorageBufferOffsetAlignment = {align}",
                self.name
            )));
        }
        let bytes = ((count * size_of::<T>()) as u64)
            .next_multiple_of(16)
            .min(self.physical_bytes - offset);
        Ok(BufferArg {
            memory: &self.memory,
            raw: self.memory.raw,
            offset,
            bytes,
            name: &self.name,
        })
    }

    /// The mapping to copy through, or `None` when the copy must take the staging path: the
    /// memory is not host-visible and coherent, or the device runs as device-local only.
    fn mapped(&self) -> Option<*mut u8> {
        if self.memory.gpu.memory == MemoryMode::DeviceLocal {
            return None;
        }
        let a = self.memory.allocation.as_ref()?;
        let coherent = a
            .memory_properties()
            .contains(vk::MemoryPropertyFlags::HOST_COHERENT);
        a.mapped_ptr()
            .filter(|_| coherent)
            .map(|p| p.as_ptr() as *mut u8)
    }

    fn check_range(&self, offset: usize, count: usize) -> GpuResult<()> {
        if offset.checked_add(count).is_none_or(|end| end > self.len) {
            return Err(GpuError::InvalidArgument(format!(
                "buffer {:?}: range {offset}..{} is outside its {} elements",
                self.name,
                offset + count,
                self.len
            )));
        }
        Ok(())
    }

    /// Writes `data` starting at element `offset`. Takes the buffer mutably: a write through
    /// the mapping must not alias a [`BufferArg`] or a read, and no recorded GPU work may be
    /// using the buffer (submissions wait for completion).
    pub fn write(&mut self, offset: usize, data: &[T]) -> GpuResult<()> {
        self.check_range(offset, data.len())?;
        if data.is_empty() {
            return Ok(());
        }
        let byte_offset = (offset * size_of::<T>()) as u64;
        if let Some(ptr) = self.mapped() {
            let src = bytemuck::cast_slice::<T, u8>(data);
            unsafe {
                std::ptr::copy_nonoverlapping(
                    src.as_ptr(),
                    ptr.add(byte_offset as usize),
                    src.len(),
                )
            };
            return Ok(());
        }
        let mut staging = Staging::new(
            &self.memory.gpu,
            &format!("{} (upload staging)", self.name),
            std::mem::size_of_val(data) as u64,
            MemoryLocation::CpuToGpu,
        )?;
        staging
            .slice_mut()
            .copy_from_slice(bytemuck::cast_slice(data));
        self.memory
            .gpu
            .staging_copies
            .fetch_add(1, Ordering::Relaxed);
        self.memory
            .gpu
            .submit_timed(|rec| {
                rec.copy_raw(staging.raw, 0, self.memory.raw, byte_offset, staging.bytes);
                Ok(())
            })
            .map(|_| ())
    }

    /// Reads the whole buffer back. No GPU work may be writing it.
    pub fn read(&self) -> GpuResult<Vec<T>> {
        self.read_range(0, self.len)
    }

    /// Reads `count` elements starting at `offset`.
    pub fn read_range(&self, offset: usize, count: usize) -> GpuResult<Vec<T>> {
        self.check_range(offset, count)?;
        let mut out = vec![T::zeroed(); count];
        if count == 0 {
            return Ok(out);
        }
        let byte_offset = (offset * size_of::<T>()) as u64;
        let dst = bytemuck::cast_slice_mut::<T, u8>(&mut out);
        if let Some(ptr) = self.mapped() {
            unsafe {
                std::ptr::copy_nonoverlapping(
                    ptr.add(byte_offset as usize),
                    dst.as_mut_ptr(),
                    dst.len(),
                )
            };
            return Ok(out);
        }
        let mut staging = Staging::new(
            &self.memory.gpu,
            &format!("{} (readback staging)", self.name),
            dst.len() as u64,
            MemoryLocation::GpuToCpu,
        )?;
        self.memory.gpu.submit_timed(|rec| {
            rec.copy_raw(self.memory.raw, byte_offset, staging.raw, 0, staging.bytes);
            Ok(())
        })?;
        dst.copy_from_slice(staging.slice_mut());
        self.memory
            .gpu
            .staging_copies
            .fetch_add(1, Ordering::Relaxed);
        Ok(out)
    }
}

/// A host-visible buffer used only for one upload or readback to non-mappable memory.
struct Staging {
    gpu: Arc<GpuInner>,
    raw: vk::Buffer,
    bytes: u64,
    allocation: Option<Allocation>,
}

impl Staging {
    fn new(
        gpu: &Arc<GpuInner>,
        name: &str,
        bytes: u64,
        location: MemoryLocation,
    ) -> GpuResult<Self> {
        let inner = gpu.clone();
        let _layer = inner.layer();
        let create = vk::BufferCreateInfo::default()
            .size(bytes)
            .usage(vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST);
        let raw =
            unsafe { inner.device.create_buffer(&create, None) }.vk("vkCreateBuffer", name)?;
        let requirements = unsafe { inner.device.get_buffer_memory_requirements(raw) };
        let allocation = inner
            .allocator
            .lock()
            .unwrap()
            .allocate(&AllocationCreateDesc {
                name,
                requirements,
                location,
                linear: true,
                allocation_scheme: AllocationScheme::GpuAllocatorManaged,
            });
        let allocation = match allocation {
            Ok(a) => a,
            Err(source) => {
                unsafe { inner.device.destroy_buffer(raw, None) };
                return Err(GpuError::Allocation {
                    object: name.into(),
                    bytes,
                    source,
                });
            }
        };
        let bound = unsafe {
            inner
                .device
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        };
        inner.meter.add(allocation.size());
        let staging = Staging {
            gpu: inner,
            raw,
            bytes,
            allocation: Some(allocation),
        };
        bound.vk("vkBindBufferMemory", name)?;
        Ok(staging)
    }

    fn slice_mut(&mut self) -> &mut [u8] {
        let a = self.allocation.as_ref().expect("live staging allocation");
        let ptr = a
            .mapped_ptr()
            .expect("staging memory is host-visible")
            .as_ptr() as *mut u8;
        unsafe { std::slice::from_raw_parts_mut(ptr, self.bytes as usize) }
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        let _layer = self.gpu.layer();
        if let Some(a) = self.allocation.take() {
            self.gpu.meter.sub(a.size());
            let _ = self.gpu.allocator.lock().unwrap().free(a);
        }
        unsafe { self.gpu.device.destroy_buffer(self.raw, None) };
    }
}
