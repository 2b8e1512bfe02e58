//! The kernels of every store, built once per device and shared (lavapipe compiles a pipeline
//! at its first dispatch, so stores must not rebuild them).

use crate::gpu::{Gpu, GpuBuffer, GpuResult, Kernel};
use crate::hash::HashKernels;
use crate::kernels::store;
use crate::voxel::SortUnique;
use bytemuck::Pod;
use glam::{Vec3, Vec4};
use std::sync::{Arc, Mutex};

/// Every store kernel, plus the hash kernels and the sort + unique step they use.
pub struct StoreKernels {
    pub(crate) gpu: Gpu,
    pub(crate) hash: Arc<HashKernels>,
    pub(crate) fill_marble: Kernel,
    pub(crate) hash_lookup: Kernel,
    pub(crate) octree_nodes: Kernel,
    pub(crate) octree_link: Kernel,
    pub(crate) octree_average: Kernel,
    pub(crate) octree_lookup: Kernel,
    pub(crate) tiletree_texels: Kernel,
    pub(crate) tiletree_dilate: Kernel,
    pub(crate) tiletree_scatter: Kernel,
    pub(crate) tiletree_lookup: Kernel,
    pub(crate) unique: Mutex<SortUnique>,
}

impl StoreKernels {
    /// Builds every kernel for `gpu`.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<StoreKernels>> {
        Ok(Arc::new(StoreKernels {
            gpu: gpu.clone(),
            hash: HashKernels::new(gpu)?,
            fill_marble: Kernel::new(gpu, &store::FILL_MARBLE)?,
            hash_lookup: Kernel::new(gpu, &store::HASH_LOOKUP)?,
            octree_nodes: Kernel::new(gpu, &store::OCTREE_NODES)?,
            octree_link: Kernel::new(gpu, &store::OCTREE_LINK)?,
            octree_average: Kernel::new(gpu, &store::OCTREE_AVERAGE)?,
            octree_lookup: Kernel::new(gpu, &store::OCTREE_LOOKUP)?,
            tiletree_texels: Kernel::new(gpu, &store::TILETREE_TEXELS)?,
            tiletree_dilate: Kernel::new(gpu, &store::TILETREE_DILATE)?,
            tiletree_scatter: Kernel::new(gpu, &store::TILETREE_SCATTER)?,
            tiletree_lookup: Kernel::new(gpu, &store::TILETREE_LOOKUP)?,
            unique: Mutex::new(SortUnique::new(gpu)?),
        }))
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}

/// Uploads `points`, runs `kernel` with `make(points, results)` as push block, reads back.
pub(crate) fn run_lookup<P: Pod>(
    kernels: &StoreKernels,
    kernel: &Kernel,
    points: &[Vec3],
    push: impl FnOnce(u64, u64) -> P,
) -> GpuResult<Vec<Vec4>> {
    let gpu = &kernels.gpu;
    let flat: Vec<f32> = points.iter().flat_map(|p| p.to_array()).collect();
    let pts = GpuBuffer::from_slice(gpu, "store lookup points", &flat)?;
    let out = GpuBuffer::<[f32; 4]>::new(gpu, "store lookup results", points.len())?;
    let p = push(pts.address(), out.address());
    gpu.submit(|rec| rec.dispatch(kernel, kernel.groups_for(points.len() as u64), &[], &p))?;
    Ok(out.read()?.into_iter().map(Vec4::from_array).collect())
}
