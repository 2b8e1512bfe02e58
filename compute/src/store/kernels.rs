//! What the stores share on one device: their kernels come from the device's kernel cache at
//! their first use (a store never builds the pipelines of another kind); the hash contexts
//! and the sort + unique step keep their scratch here between builds.

use super::lookup_cpu::StoreSample;
use super::Filter;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Kernel, KernelDef, Recorder};
use crate::hash::perfect::PerfectKernels;
use crate::hash::HashKernels;
use crate::shader_constants::STORE_LOOKUP_SAMPLE;
use crate::voxel::SortUnique;
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

/// What a store's lookup harness computes at each point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LookupMode {
    /// The colour lookup with this filter: one vec4 per point.
    Filtered(Filter),
    /// The sample lookup a relief reads ([`StoreSample`]): the trilinear (TileTree: bilinear)
    /// sum, its coverage and the gradient of alpha; two vec4 per point.
    Sample,
}

impl LookupMode {
    /// The harness's `mode` push constant.
    pub(crate) fn code(self) -> u32 {
        match self {
            LookupMode::Filtered(filter) => (filter == Filter::Trilinear) as u32,
            LookupMode::Sample => STORE_LOOKUP_SAMPLE,
        }
    }

    /// vec4 results per point.
    fn words(self) -> usize {
        match self {
            LookupMode::Filtered(_) => 1,
            LookupMode::Sample => 2,
        }
    }
}

impl From<Filter> for LookupMode {
    fn from(filter: Filter) -> LookupMode {
        LookupMode::Filtered(filter)
    }
}

/// Records one lookup dispatch of a store's kernel with the push block it builds from the call.
type RecordFn<'a> = Box<dyn for<'b> Fn(&mut Recorder<'_>, LookupCall<'b>) -> GpuResult<()> + 'a>;

/// A lookup whose points are already on the device, run as often as a benchmark needs: each
/// [`TimedLookup::run`] is one dispatch between two GPU timestamps, so uploads and read-backs
/// stay out of the measured time.
pub struct TimedLookup<'a> {
    gpu: Gpu,
    points: GpuBuffer<f32>,
    normals: Option<GpuBuffer<f32>>,
    results: GpuBuffer<[f32; 4]>,
    kernel: Arc<Kernel>,
    mode: LookupMode,
    record: RecordFn<'a>,
}

impl TimedLookup<'_> {
    /// One lookup of every point; returns its GPU time in milliseconds.
    pub fn run(&self) -> GpuResult<f64> {
        let n = (self.results.len() / self.mode.words()) as u32;
        let call = LookupCall {
            kernel: &self.kernel,
            groups: self.kernel.groups_for(n as u64),
            points: self.points.address(),
            normals: self
                .normals
                .as_ref()
                .map_or(DeviceAddress::NULL, GpuBuffer::address),
            results: self.results.address(),
            n,
            mode: self.mode.code(),
        };
        let ((), t) = self.gpu.submit_timed(|rec| {
            rec.timestamp()?;
            (self.record)(rec, call)?;
            rec.timestamp()
        })?;
        Ok((t[1] - t[0]) * 1e-6)
    }

    /// The samples of the last run of a [`LookupMode::Sample`] lookup, one per point.
    pub fn samples(&self) -> GpuResult<Vec<StoreSample>> {
        debug_assert_eq!(self.mode, LookupMode::Sample);
        Ok(self
            .results
            .read()?
            .chunks_exact(2)
            .map(|r| StoreSample {
                sum: Vec4::from_array(r[0]),
                coverage: r[1][0],
                gradient: Vec3::new(r[1][1], r[1][2], r[1][3]),
            })
            .collect())
    }

    /// The results of the last run: one per point (two for [`LookupMode::Sample`]).
    pub fn results(&self) -> GpuResult<Vec<Vec4>> {
        Ok(self
            .results
            .read()?
            .into_iter()
            .map(Vec4::from_array)
            .collect())
    }
}

/// One dispatch of a store's lookup kernel: the kernel and its groups, and what its push block
/// takes besides the store.
#[derive(Clone, Copy)]
pub(crate) struct LookupCall<'a> {
    pub kernel: &'a Kernel,
    pub groups: [u32; 3],
    pub points: DeviceAddress<'a>,
    /// Null when no normals were given.
    pub normals: DeviceAddress<'a>,
    pub results: DeviceAddress<'a>,
    /// Points, one result each.
    pub n: u32,
    /// [`LookupMode::code`].
    pub mode: u32,
}

/// Every store's [`SparseStore::timed_lookup`](super::SparseStore::timed_lookup): fetches
/// `kernel` from the device's cache, uploads `points` (and `normals` when given) and prepares
/// `dispatch`, which records the kernel with the store's push block built from the
/// [`LookupCall`]. Timed or not, every lookup goes through here.
pub(crate) fn timed_lookup<'a>(
    kernels: &'a StoreKernels,
    kernel: &'static KernelDef,
    points: &[Vec3],
    normals: &[Vec3],
    mode: LookupMode,
    dispatch: impl for<'b> Fn(&mut Recorder<'_>, LookupCall<'b>) -> GpuResult<()> + 'a,
) -> GpuResult<TimedLookup<'a>> {
    let gpu = &kernels.gpu;
    let flat = |v: &[Vec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f32>>();
    let normals = if normals.is_empty() {
        None
    } else {
        Some(GpuBuffer::from_slice(
            gpu,
            "store lookup normals",
            &flat(normals),
        )?)
    };
    Ok(TimedLookup {
        gpu: gpu.clone(),
        points: GpuBuffer::from_slice(gpu, "store lookup points", &flat(points))?,
        normals,
        results: GpuBuffer::zeroed(gpu, "store lookup results", points.len() * mode.words())?,
        kernel: gpu.kernel(kernel)?,
        mode,
        record: Box::new(dispatch),
    })
}
