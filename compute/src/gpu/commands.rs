//! Recording and submitting work: dispatches, fills, copies, barriers and timestamps, submitted
//! once and waited for (the right default for tools and tests).

use super::buffer::{BufferArg, GpuBuffer};
use super::context::{Gpu, GpuInner};
use super::error::{GpuError, GpuResult, VkContext};
use super::keep_alive::KeepAlive;
use super::kernel::{BindingKind, Kernel};
#[cfg(debug_assertions)]
use super::push::check_push_block;
use super::push::{push_bytes, PushBlock};
use super::submissions::PROFILED_DISPATCHES;
use ash::vk;
use bytemuck::Pod;

/// Most timestamps one submission may write.
pub const MAX_TIMESTAMPS: u32 = 256;

/// Records commands into one command buffer. Every command that follows a write is preceded
/// by a memory barrier, so consecutive dispatches always see each other's results. The
/// recorder holds the memory of every buffer its commands use (bound, addressed from a push
/// block, filled or copied) until the submission has completed.
pub struct Recorder<'g> {
    gpu: &'g GpuInner,
    cmd: vk::CommandBuffer,
    pending_write: bool,
    queries: vk::QueryPool,
    timestamps: u32,
    used: KeepAlive,
    /// While profiling: the query pool of the dispatches' brackets and each one's kernel.
    profile: Option<(vk::QueryPool, Vec<&'static str>)>,
}

impl Gpu {
    /// Records with `record`, submits, and waits for completion.
    pub fn submit<R>(
        &self,
        record: impl FnOnce(&mut Recorder<'_>) -> GpuResult<R>,
    ) -> GpuResult<R> {
        self.submit_timed(record).map(|(r, _)| r)
    }

    /// Like [`Gpu::submit`], and also returns the times of every [`Recorder::timestamp`] in
    /// nanoseconds after the first one (which is 0), in recording order: only differences
    /// within one submission mean anything (see [`elapsed_ns`]).
    pub fn submit_timed<R>(
        &self,
        record: impl FnOnce(&mut Recorder<'_>) -> GpuResult<R>,
    ) -> GpuResult<(R, Vec<f64>)> {
        self.inner.submit_timed(record)
    }
}

impl GpuInner {
    /// See [`Gpu::submit_timed`]; buffers submit their copies through this.
    pub(crate) fn submit_timed<R>(
        &self,
        record: impl FnOnce(&mut Recorder<'_>) -> GpuResult<R>,
    ) -> GpuResult<(R, Vec<f64>)> {
        let inner = self;
        let device = &inner.device;
        // Held for every call below but not while `record` runs: the recorder's commands hold
        // it themselves, so a closure that waits on another thread cannot hold it meanwhile.
        // Declared before the pool guard, so that guard's destruction is held too.
        let mut layer = inner.layer();
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(inner.queue_family)
            .flags(vk::CommandPoolCreateFlags::TRANSIENT);
        let pool = unsafe { device.create_command_pool(&pool_info, None) }
            .vk("vkCreateCommandPool", "submission")?;
        let guard = PoolGuard {
            device,
            pool,
            fence: vk::Fence::null(),
            queries: vk::QueryPool::null(),
            bracket: vk::QueryPool::null(),
            profile: vk::QueryPool::null(),
        };
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        let cmd = unsafe { device.allocate_command_buffers(&alloc) }
            .vk("vkAllocateCommandBuffers", "submission")?[0];
        unsafe {
            device.begin_command_buffer(
                cmd,
                &vk::CommandBufferBeginInfo::default()
                    .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT),
            )
        }
        .vk("vkBeginCommandBuffer", "submission")?;
        let mut guard = guard;
        if inner.submissions.timing() {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(2);
            guard.bracket = unsafe { device.create_query_pool(&info, None) }
                .vk("vkCreateQueryPool", "submission timing")?;
            unsafe {
                device.cmd_reset_query_pool(cmd, guard.bracket, 0, 2);
                device.cmd_write_timestamp(
                    cmd,
                    vk::PipelineStageFlags::TOP_OF_PIPE,
                    guard.bracket,
                    0,
                );
            }
        }
        if inner.submissions.profiling() {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(2 * PROFILED_DISPATCHES);
            guard.profile = unsafe { device.create_query_pool(&info, None) }
                .vk("vkCreateQueryPool", "dispatch profile")?;
            unsafe { device.cmd_reset_query_pool(cmd, guard.profile, 0, 2 * PROFILED_DISPATCHES) };
        }
        let mut rec = Recorder {
            gpu: inner,
            cmd,
            pending_write: false,
            queries: vk::QueryPool::null(),
            timestamps: 0,
            used: KeepAlive::default(),
            profile: (guard.profile != vk::QueryPool::null()).then(|| (guard.profile, Vec::new())),
        };
        drop(layer);
        let result = record(&mut rec);
        layer = inner.layer();
        guard.queries = rec.queries;
        let value = result?;
        // Make every write visible to the host that reads mapped memory after the wait.
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE)
            .dst_access_mask(vk::AccessFlags::HOST_READ | vk::AccessFlags::HOST_WRITE);
        unsafe {
            if guard.bracket != vk::QueryPool::null() {
                device.cmd_write_timestamp(
                    cmd,
                    vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                    guard.bracket,
                    1,
                );
            }
            device.cmd_pipeline_barrier(
                cmd,
                vk::PipelineStageFlags::ALL_COMMANDS,
                vk::PipelineStageFlags::HOST,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            );
            device
                .end_command_buffer(cmd)
                .vk("vkEndCommandBuffer", "submission")?;
        }
        guard.fence = unsafe { device.create_fence(&vk::FenceCreateInfo::default(), None) }
            .vk("vkCreateFence", "submission")?;
        let cmds = [cmd];
        let submit = [vk::SubmitInfo::default().command_buffers(&cmds)];
        {
            let queue = inner.queue.lock().unwrap();
            unsafe { device.queue_submit(*queue, &submit, guard.fence) }
                .vk("vkQueueSubmit", "submission")?;
        }
        match unsafe { device.wait_for_fences(&[guard.fence], true, u64::MAX) } {
            Ok(()) => {}
            Err(vk::Result::ERROR_DEVICE_LOST) => {
                return Err(GpuError::Vulkan {
                    call: "vkWaitForFences",
                    object: "submission (device lost: a kernel faulted or hung)".into(),
                    result: vk::Result::ERROR_DEVICE_LOST,
                })
            }
            Err(result) => {
                return Err(GpuError::Vulkan {
                    call: "vkWaitForFences",
                    object: "submission".into(),
                    result,
                })
            }
        }
        inner.submissions.waited();
        let info = &inner.info;
        let ns = |start: u64, end: u64| {
            elapsed_ns(
                start,
                end,
                info.timestamp_valid_bits,
                info.timestamp_period_ns,
            )
        };
        if guard.bracket != vk::QueryPool::null() {
            let raw = query_ticks(device, guard.bracket, 2, "submission timing")?;
            inner.submissions.add_device_ns(ns(raw[0], raw[1]));
        }
        if let Some((pool, kernels)) = &rec.profile {
            let timed = kernels.len().min(PROFILED_DISPATCHES as usize);
            let raw = query_ticks(device, *pool, 2 * timed, "dispatch profile")?;
            for (i, kernel) in kernels.iter().enumerate() {
                let time = (i < timed).then(|| ns(raw[2 * i], raw[2 * i + 1]));
                inner.submissions.add_dispatch(kernel, time);
            }
        }
        let times = match query_ticks(device, rec.queries, rec.timestamps as usize, "timestamps")? {
            raw if raw.is_empty() => Vec::new(),
            raw => raw.iter().map(|&t| ns(raw[0], t)).collect(),
        };
        drop(rec);
        drop(guard);
        drop(layer);
        Ok((value, times))
    }
}

/// The first `count` timestamps of `pool`, in ticks, once written (none when `count` is 0).
fn query_ticks(
    device: &ash::Device,
    pool: vk::QueryPool,
    count: usize,
    what: &str,
) -> GpuResult<Vec<u64>> {
    let mut raw = vec![0u64; count];
    if count > 0 {
        unsafe {
            device.get_query_pool_results(
                pool,
                0,
                &mut raw,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .vk("vkGetQueryPoolResults", what)?;
    }
    Ok(raw)
}

/// Nanoseconds from tick `start` to tick `end` of a queue whose timestamps have `valid_bits`
/// significant bits and tick every `period_ns`. Only the low `valid_bits` bits count and the
/// counter wraps at `2^valid_bits`, so the difference is taken in ticks, modulo that, before
/// converting: a raw tick count converted to `f64` first would also lose precision on GPUs whose
/// counters start far from zero.
pub fn elapsed_ns(start: u64, end: u64, valid_bits: u32, period_ns: f32) -> f64 {
    let mask = if valid_bits >= 64 {
        u64::MAX
    } else {
        (1u64 << valid_bits) - 1
    };
    let ticks = end.wrapping_sub(start) & mask;
    ticks as f64 * period_ns as f64
}

struct PoolGuard<'d> {
    device: &'d ash::Device,
    pool: vk::CommandPool,
    fence: vk::Fence,
    queries: vk::QueryPool,
    /// The two timestamps around the whole submission while timing is on.
    bracket: vk::QueryPool,
    /// The timestamps around each dispatch while profiling.
    profile: vk::QueryPool,
}

impl Drop for PoolGuard<'_> {
    fn drop(&mut self) {
        unsafe {
            if self.fence != vk::Fence::null() {
                self.device.destroy_fence(self.fence, None);
            }
            if self.queries != vk::QueryPool::null() {
                self.device.destroy_query_pool(self.queries, None);
            }
            for pool in [self.bracket, self.profile] {
                if pool != vk::QueryPool::null() {
                    self.device.destroy_query_pool(pool, None);
                }
            }
            self.device.destroy_command_pool(self.pool, None);
        }
    }
}

impl Recorder<'_> {
    /// Emits the barrier owed to the last write, if any.
    fn settle(&mut self) {
        if self.pending_write {
            self.barrier();
        }
    }

    /// A full memory barrier between compute and transfer work (and the reads of indirect
    /// dispatch arguments).
    pub fn barrier(&mut self) {
        let _layer = self.gpu.layer();
        let stages = vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER;
        let barrier = vk::MemoryBarrier::default()
            .src_access_mask(vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE)
            .dst_access_mask(
                vk::AccessFlags::SHADER_READ
                    | vk::AccessFlags::SHADER_WRITE
                    | vk::AccessFlags::TRANSFER_READ
                    | vk::AccessFlags::TRANSFER_WRITE
                    | vk::AccessFlags::INDIRECT_COMMAND_READ,
            );
        unsafe {
            self.gpu.device.cmd_pipeline_barrier(
                self.cmd,
                stages,
                stages | vk::PipelineStageFlags::DRAW_INDIRECT,
                vk::DependencyFlags::empty(),
                &[barrier],
                &[],
                &[],
            )
        };
        self.pending_write = false;
    }

    /// Dispatches `kernel` over `groups` workgroups with descriptor `bindings` (by GLSL name)
    /// and push constants `push`.
    ///
    /// # Errors
    /// [`GpuError::KernelInterface`] when a binding is missing, unknown or repeated, when
    /// `P`'s size differs from the GLSL push-constant block, or (in debug builds) when a field
    /// of `P` differs from its GLSL member in name, offset or type; [`GpuError::OverLimit`]
    /// when a buffer is larger than `maxStorageBufferRange` (large data goes through device
    /// addresses).
    pub fn dispatch<P: PushBlock>(
        &mut self,
        kernel: &Kernel,
        groups: [u32; 3],
        bindings: &[(&str, BufferArg<'_>)],
        push: &P,
    ) -> GpuResult<()> {
        self.launch(kernel, Launch::Direct(groups), bindings, push)
    }

    /// As [`Recorder::dispatch`], with the workgroup counts read on the device from the 3
    /// words at `word` of `args` (written by an earlier dispatch: a count of 0 runs nothing,
    /// which is how a kernel choice made on the device skips work).
    ///
    /// # Errors
    /// As [`Recorder::dispatch`].
    pub fn dispatch_indirect<P: PushBlock>(
        &mut self,
        kernel: &Kernel,
        args: &GpuBuffer<u32>,
        word: u64,
        bindings: &[(&str, BufferArg<'_>)],
        push: &P,
    ) -> GpuResult<()> {
        if (word + 3) * 4 > args.bytes() {
            return Err(GpuError::KernelInterface {
                kernel: kernel.def.name,
                problem: format!(
                    "indirect counts at word {word} lie past the end of {} ({} bytes)",
                    args.name(),
                    args.bytes()
                ),
            });
        }
        self.used.hold(args.memory());
        self.launch(
            kernel,
            Launch::Indirect(args.raw(), word * 4),
            bindings,
            push,
        )
    }

    fn launch<P: PushBlock>(
        &mut self,
        kernel: &Kernel,
        launch: Launch,
        bindings: &[(&str, BufferArg<'_>)],
        push: &P,
    ) -> GpuResult<()> {
        let def = kernel.def;
        if !std::ptr::eq(&*kernel.gpu, self.gpu) {
            return Err(GpuError::KernelInterface {
                kernel: def.name,
                problem: "the kernel belongs to another device".into(),
            });
        }
        let push_bytes = push_bytes(push);
        if push_bytes.len() as u32 != def.push_constant_bytes {
            return Err(GpuError::KernelInterface {
                kernel: def.name,
                problem: format!(
                    "push constants are {} bytes on the host but {} bytes in GLSL",
                    push_bytes.len(),
                    def.push_constant_bytes
                ),
            });
        }
        #[cfg(debug_assertions)]
        check_push_block::<P>(def).map_err(|problem| GpuError::KernelInterface {
            kernel: def.name,
            problem,
        })?;
        let range_limit = self.gpu.info.max_storage_buffer_range;
        let mut infos = Vec::with_capacity(def.bindings.len());
        for (name, _) in bindings {
            if !def.bindings.iter().any(|b| b.name == *name) {
                let known: Vec<_> = def.bindings.iter().map(|b| b.name).collect();
                return Err(GpuError::KernelInterface {
                    kernel: def.name,
                    problem: format!("no binding named {name:?} (bindings: {known:?})"),
                });
            }
        }
        for b in def.bindings {
            let mut found = bindings.iter().filter(|(n, _)| *n == b.name);
            let Some((_, arg)) = found.next() else {
                return Err(GpuError::KernelInterface {
                    kernel: def.name,
                    problem: format!(
                        "binding {:?} (binding = {}) was not given",
                        b.name, b.binding
                    ),
                });
            };
            if found.next().is_some() {
                return Err(GpuError::KernelInterface {
                    kernel: def.name,
                    problem: format!("binding {:?} was given twice", b.name),
                });
            }
            if b.kind == BindingKind::StorageBuffer && arg.bytes > range_limit {
                return Err(GpuError::OverLimit {
                    what: format!(
                        "kernel {} binding {:?} (buffer {:?})",
                        def.name, b.name, arg.name
                    ),
                    requested: arg.bytes,
                    limit_name: "maxStorageBufferRange",
                    limit: range_limit,
                });
            }
            infos.push((
                b,
                [vk::DescriptorBufferInfo::default()
                    .buffer(arg.raw)
                    .offset(arg.offset)
                    .range(arg.bytes)],
            ));
        }
        let writes: Vec<_> = infos
            .iter()
            .map(|(b, info)| {
                vk::WriteDescriptorSet::default()
                    .dst_binding(b.binding)
                    .descriptor_type(match b.kind {
                        BindingKind::StorageBuffer => vk::DescriptorType::STORAGE_BUFFER,
                        BindingKind::UniformBuffer => vk::DescriptorType::UNIFORM_BUFFER,
                    })
                    .buffer_info(info)
            })
            .collect();
        if matches!(launch, Launch::Direct(groups) if groups.contains(&0)) {
            return Ok(());
        }
        push.keep_alive(&mut self.used);
        for (_, arg) in bindings {
            self.used.hold(arg.memory);
        }
        self.settle();
        let d = &self.gpu.device;
        let _layer = self.gpu.layer();
        unsafe {
            d.cmd_bind_pipeline(self.cmd, vk::PipelineBindPoint::COMPUTE, kernel.pipeline);
            if !writes.is_empty() {
                self.gpu.push_descriptor.cmd_push_descriptor_set(
                    self.cmd,
                    vk::PipelineBindPoint::COMPUTE,
                    kernel.pipeline_layout,
                    0,
                    &writes,
                );
            }
            if !push_bytes.is_empty() {
                d.cmd_push_constants(
                    self.cmd,
                    kernel.pipeline_layout,
                    vk::ShaderStageFlags::COMPUTE,
                    0,
                    &push_bytes,
                );
            }
            let timed = match &mut self.profile {
                Some((pool, kernels)) => {
                    let i = kernels.len() as u32;
                    kernels.push(def.name);
                    (i < PROFILED_DISPATCHES).then_some((*pool, 2 * i))
                }
                None => None,
            };
            if let Some((pool, q)) = timed {
                d.cmd_write_timestamp(self.cmd, vk::PipelineStageFlags::TOP_OF_PIPE, pool, q);
            }
            match launch {
                Launch::Direct([x, y, z]) => d.cmd_dispatch(self.cmd, x, y, z),
                Launch::Indirect(buffer, offset) => {
                    d.cmd_dispatch_indirect(self.cmd, buffer, offset)
                }
            }
            if let Some((pool, q)) = timed {
                d.cmd_write_timestamp(
                    self.cmd,
                    vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                    pool,
                    q + 1,
                );
            }
        }
        self.pending_write = true;
        Ok(())
    }

    /// Fills the whole buffer with copies of the 32-bit `word`.
    pub fn fill<T: Pod>(&mut self, buffer: &GpuBuffer<T>, word: u32) {
        self.used.hold(buffer.memory());
        self.fill_raw(buffer.raw(), 0, buffer.bytes() & !3, word);
    }

    pub(crate) fn fill_raw(&mut self, buffer: vk::Buffer, offset: u64, bytes: u64, word: u32) {
        if bytes == 0 {
            return;
        }
        self.settle();
        let _layer = self.gpu.layer();
        unsafe {
            self.gpu
                .device
                .cmd_fill_buffer(self.cmd, buffer, offset, bytes, word)
        };
        self.pending_write = true;
    }

    /// Copies `count` elements from `src[src_offset..]` to `dst[dst_offset..]`.
    pub fn copy<T: Pod>(
        &mut self,
        src: &GpuBuffer<T>,
        src_offset: usize,
        dst: &GpuBuffer<T>,
        dst_offset: usize,
        count: usize,
    ) -> GpuResult<()> {
        if src_offset + count > src.len() || dst_offset + count > dst.len() {
            return Err(GpuError::InvalidArgument(format!(
                "copy of {count} elements from {:?}[{src_offset}..] ({} long) to {:?}[{dst_offset}..] ({} long) is out of range",
                src.name(),
                src.len(),
                dst.name(),
                dst.len()
            )));
        }
        let e = size_of::<T>() as u64;
        self.used.hold(src.memory());
        self.used.hold(dst.memory());
        self.copy_raw(
            src.raw(),
            src_offset as u64 * e,
            dst.raw(),
            dst_offset as u64 * e,
            count as u64 * e,
        );
        Ok(())
    }

    /// Copies the first `bytes` bytes of `src` to the start of `dst`, whatever their element
    /// types.
    pub(crate) fn copy_bytes<A: Pod, B: Pod>(
        &mut self,
        src: &GpuBuffer<A>,
        dst: &GpuBuffer<B>,
        bytes: u64,
    ) {
        self.used.hold(src.memory());
        self.used.hold(dst.memory());
        self.copy_raw(src.raw(), 0, dst.raw(), 0, bytes);
    }

    pub(crate) fn copy_raw(
        &mut self,
        src: vk::Buffer,
        src_offset: u64,
        dst: vk::Buffer,
        dst_offset: u64,
        bytes: u64,
    ) {
        if bytes == 0 {
            return;
        }
        self.settle();
        let region = [vk::BufferCopy::default()
            .src_offset(src_offset)
            .dst_offset(dst_offset)
            .size(bytes)];
        let _layer = self.gpu.layer();
        unsafe { self.gpu.device.cmd_copy_buffer(self.cmd, src, dst, &region) };
        self.pending_write = true;
    }

    /// Writes a timestamp once all previously recorded work has finished; the times come back
    /// from [`Gpu::submit_timed`].
    ///
    /// # Errors
    /// More than [`MAX_TIMESTAMPS`] in one submission, or a query-pool creation failure.
    pub fn timestamp(&mut self) -> GpuResult<()> {
        let _layer = self.gpu.layer();
        if self.queries == vk::QueryPool::null() {
            let info = vk::QueryPoolCreateInfo::default()
                .query_type(vk::QueryType::TIMESTAMP)
                .query_count(MAX_TIMESTAMPS);
            self.queries = unsafe { self.gpu.device.create_query_pool(&info, None) }
                .vk("vkCreateQueryPool", "timestamps")?;
            unsafe {
                self.gpu
                    .device
                    .cmd_reset_query_pool(self.cmd, self.queries, 0, MAX_TIMESTAMPS)
            };
        }
        if self.timestamps >= MAX_TIMESTAMPS {
            return Err(GpuError::InvalidArgument(format!(
                "more than {MAX_TIMESTAMPS} timestamps in one submission"
            )));
        }
        self.settle();
        unsafe {
            self.gpu.device.cmd_write_timestamp(
                self.cmd,
                vk::PipelineStageFlags::BOTTOM_OF_PIPE,
                self.queries,
                self.timestamps,
            )
        };
        self.timestamps += 1;
        Ok(())
    }
}

/// How a dispatch gets its workgroup counts.
#[derive(Clone, Copy)]
enum Launch {
    Direct([u32; 3]),
    /// The buffer and byte offset of 3 words of counts.
    Indirect(vk::Buffer, u64),
}
