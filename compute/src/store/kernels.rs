//! What the stores share on one device: their kernels come from the device's kernel cache at
//! their first use (a store never builds the pipelines of another kind); the hash contexts
//! and the sort + unique step keep their scratch here between builds.

use crate::gpu::{Gpu, GpuBuffer, GpuResult, KernelDef, Recorder};
use crate::hash::perfect::PerfectKernels;
use crate::hash::HashKernels;
use crate::voxel::SortUnique;
use bytemuck::Pod;
use glam::{Vec3, Vec4};
use std::sync::{Arc, Mutex};

/// The stores' shared context on one device.
pub struct StoreKernels {
    pub(crate) gpu: Gpu,
    pub(crate) hash: Arc<HashKernels>,
    pub(crate) perfect: Arc<PerfectKernels>,
    pub(crate) unique: Mutex<SortUnique>,
}

impl StoreKernels {
    /// The context for `gpu`; builds no pipeline.
    pub fn new(gpu: &Gpu) -> GpuResult<Arc<StoreKernels>> {
        Ok(Arc::new(StoreKernels {
            gpu: gpu.clone(),
            hash: HashKernels::new(gpu)?,
            perfect: PerfectKernels::new(gpu)?,
            unique: Mutex::new(SortUnique::new(gpu)?),
        }))
    }

    /// The device.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}

/// Records one lookup dispatch.
type RecordFn<'a> = Box<dyn Fn(&mut Recorder<'_>) -> GpuResult<()> + 'a>;

/// A lookup whose points are already on the device, run as often as a benchmark needs: each
/// [`TimedLookup::run`] is one dispatch between two GPU timestamps, so uploads and read-backs
/// stay out of the measured time.
pub struct TimedLookup<'a> {
    gpu: Gpu,
    results: GpuBuffer<[f32; 4]>,
    // Keeps the points (and normals) alive for as long as the recorded dispatches read them.
    _inputs: Vec<GpuBuffer<f32>>,
    record: RecordFn<'a>,
}

impl TimedLookup<'_> {
    /// One lookup of every point; returns its GPU time in milliseconds.
    pub fn run(&self) -> GpuResult<f64> {
        let ((), t) = self.gpu.submit_timed(|rec| {
            rec.timestamp()?;
            (self.record)(rec)?;
            rec.timestamp()
        })?;
        Ok((t[1] - t[0]) * 1e-6)
    }

    /// The results of the last run, one per point.
    pub fn results(&self) -> GpuResult<Vec<Vec4>> {
        Ok(self
            .results
            .read()?
            .into_iter()
            .map(Vec4::from_array)
            .collect())
    }
}

/// Device addresses a lookup kernel's push block takes.
#[derive(Clone, Copy)]
pub(crate) struct LookupAddresses {
    pub points: u64,
    /// 0 when no normals were given.
    pub normals: u64,
    pub results: u64,
}

/// Uploads `points` (and `normals` when given) and prepares the lookup kernel `def` with
/// `make(addresses)` as push block: every store's lookup, timed or not, goes through here.
pub(crate) fn prepare_lookup<'a, P: Pod>(
    kernels: &'a StoreKernels,
    def: &'static KernelDef,
    points: &[Vec3],
    normals: &[Vec3],
    push: impl FnOnce(LookupAddresses) -> P,
) -> GpuResult<TimedLookup<'a>> {
    let gpu = &kernels.gpu;
    let kernel = gpu.kernel(def)?;
    let flat = |v: &[Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let mut inputs = vec![GpuBuffer::from_slice(
        gpu,
        "store lookup points",
        &flat(points),
    )?];
    if !normals.is_empty() {
        inputs.push(GpuBuffer::from_slice(
            gpu,
            "store lookup normals",
            &flat(normals),
        )?);
    }
    let results = GpuBuffer::<[f32; 4]>::zeroed(gpu, "store lookup results", points.len())?;
    let p = push(LookupAddresses {
        points: inputs[0].address(),
        normals: inputs.get(1).map_or(0, GpuBuffer::address),
        results: results.address(),
    });
    let groups = kernel.groups_for(points.len() as u64);
    Ok(TimedLookup {
        gpu: gpu.clone(),
        results,
        _inputs: inputs,
        record: Box::new(move |rec| rec.dispatch(&kernel, groups, &[], &p)),
    })
}
