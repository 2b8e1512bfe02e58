//! Batches of ray queries on the GPU: what the traversal tests and `lazysolid bench trace`
//! run. The path tracer includes the same traversal in its own kernel.

use super::device::DeviceBvh;
use super::gpu_types::{GpuRay, GpuRayHit};
use crate::kernels::render::TRACE_RAYS;
use crate::shader_constants::{CWBVH_STACK_SIZE, CWBVH_WORKGROUP_SIZE};
use lazysolid_compute::gpu::{Gpu, GpuBuffer, GpuError, GpuResult, Kernel, KernelDef, Recorder};
use std::sync::Arc;

lazysolid_compute::push_block! {
    /// Push block of `trace_rays.comp`.
    #[derive(Clone, Copy)]
    pub(crate) struct TraceRaysPush {
        first: u32,
        n: u32,
        any_hit: u32,
    }
}

/// Whether a query wants the closest hit or any hit (shadow rays).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QueryKind {
    /// The nearest intersection.
    Closest,
    /// Any intersection in range: traversal stops at the first one found.
    Any,
}

/// Bytes of shared memory a workgroup of a kernel including `render/cwbvh.glsl` needs: one
/// stack of `uvec2` entries per invocation.
pub const CWBVH_SHARED_BYTES: u32 = CWBVH_WORKGROUP_SIZE * CWBVH_STACK_SIZE * 8;
const _: () = assert!(
    CWBVH_SHARED_BYTES <= lazysolid_compute::gpu::DESIGN_SHARED_MEMORY
        && CWBVH_WORKGROUP_SIZE <= lazysolid_compute::gpu::DESIGN_WORKGROUP_INVOCATIONS
);

/// `def`, a kernel that traces through `render/cwbvh.glsl`, at [`CWBVH_WORKGROUP_SIZE`] with the
/// given specialization constants, once its traversal stacks are known to fit the device's
/// shared memory: a device with less gets an error naming the limit, not a failed pipeline.
///
/// # Errors
/// [`GpuError::OverLimit`] for `maxComputeSharedMemorySize`; pipeline creation failures.
pub(crate) fn cwbvh_kernel(
    gpu: &Gpu,
    def: &'static KernelDef,
    constants: &[(u32, u32)],
) -> GpuResult<Arc<Kernel>> {
    let limit = gpu.info().max_shared_memory;
    if CWBVH_SHARED_BYTES > limit {
        return Err(GpuError::OverLimit {
            what: format!(
                "kernel {}: traversal stacks of {CWBVH_WORKGROUP_SIZE} invocations x {CWBVH_STACK_SIZE} entries",
                def.name
            ),
            requested: CWBVH_SHARED_BYTES as u64,
            limit_name: "maxComputeSharedMemorySize",
            limit: limit as u64,
        });
    }
    gpu.kernel_with(def, CWBVH_WORKGROUP_SIZE, constants)
}

/// The ray-query kernel.
pub struct RayQueries {
    kernel: Arc<Kernel>,
}

impl RayQueries {
    /// Creates the kernel.
    ///
    /// # Errors
    /// Pipeline creation failures.
    pub fn new(gpu: &Gpu) -> GpuResult<RayQueries> {
        Ok(RayQueries {
            kernel: cwbvh_kernel(gpu, &TRACE_RAYS, &[])?,
        })
    }

    /// Records the queries of `rays` into `hits` (same length).
    ///
    /// # Errors
    /// Length mismatch or a binding over a device limit.
    pub fn record(
        &self,
        rec: &mut Recorder<'_>,
        bvh: &DeviceBvh,
        rays: &GpuBuffer<GpuRay>,
        hits: &GpuBuffer<GpuRayHit>,
        kind: QueryKind,
    ) -> GpuResult<()> {
        assert_eq!(rays.len(), hits.len(), "one hit record per ray");
        let n = rays.len() as u32;
        if n == 0 {
            return Ok(());
        }
        let [b0, b1, b2, b3, b4] = bvh.bindings();
        let bindings = [
            b0,
            b1,
            b2,
            b3,
            b4,
            ("Rays", rays.arg()),
            ("Hits", hits.arg()),
        ];
        let push = TraceRaysPush {
            first: 0,
            n,
            any_hit: (kind == QueryKind::Any) as u32,
        };
        rec.dispatch(
            &self.kernel,
            self.kernel.groups_for(n as u64),
            &bindings,
            &push,
        )
    }

    /// Uploads `rays`, traces them and reads the hits back.
    ///
    /// # Errors
    /// Allocation, dispatch or readback failures.
    pub fn run(
        &self,
        gpu: &Gpu,
        bvh: &DeviceBvh,
        rays: &[GpuRay],
        kind: QueryKind,
    ) -> GpuResult<Vec<GpuRayHit>> {
        if rays.is_empty() {
            return Ok(Vec::new());
        }
        let ray_buf = GpuBuffer::from_slice(gpu, "rays", rays)?;
        let hit_buf = GpuBuffer::<GpuRayHit>::zeroed(gpu, "ray hits", rays.len())?;
        gpu.submit(|rec| self.record(rec, bvh, &ray_buf, &hit_buf, kind))?;
        hit_buf.read()
    }
}
