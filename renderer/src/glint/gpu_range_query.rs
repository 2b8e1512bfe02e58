//! The device twins of [`super::minmax_mip`]: the min–max mip built bottom-up (one dispatch of
//! `glsl/render/glint_minmax_mip.comp` per level), and batches of range queries through
//! `glsl/render/glint_range_query.comp` by the sparse table, the mip or brute force, with the
//! same answers as their CPU twins.

use super::example::NormalExample;
use super::minmax_mip::{mip_level_offset, MinMaxMip, RangeSquare};
use super::range_table::quantize_texels;
use crate::kernels::render::{GLINT_MINMAX_MIP, GLINT_RANGE_QUERY};
use lazysolid_compute::gpu::{
    DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult, Kernel, Recorder,
};

lazysolid_compute::push_block! {
    /// Push block of `glsl/render/glint_minmax_mip.comp`.
    #[derive(Clone, Copy)]
    pub struct GlintMinMaxMipPush<'a> {
        /// The level below (edge 2 · `edge`).
        pub src: DeviceAddress<'a>,
        /// The level written.
        pub dst: DeviceAddress<'a>,
        /// Edge of the level written.
        pub edge: u32,
    }
}

lazysolid_compute::push_block! {
    /// Push block of `glsl/render/glint_range_query.comp`.
    #[derive(Clone, Copy)]
    pub struct GlintRangeQueryPush<'a> {
        /// The sparse table, the mip, or the quantized texels (by `method`).
        pub structure: DeviceAddress<'a>,
        /// The [`RangeSquare`]s.
        pub squares: DeviceAddress<'a>,
        /// One packed interval per square.
        pub results: DeviceAddress<'a>,
        /// Number of squares.
        pub count: u32,
        /// Example edge.
        pub size: u32,
        /// [`RangeMethod::code`].
        pub method: u32,
    }
}

/// How a range query is answered (all three give the same packed interval).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RangeMethod {
    /// One lookup in the sparse table ([`super::RangeTable`]), O(1).
    SparseTable,
    /// The union of the square's maximal aligned blocks of the [`MinMaxMip`].
    MinMaxMip,
    /// Every texel of the square.
    BruteForce,
}

impl RangeMethod {
    /// All methods, fastest first.
    pub const ALL: [RangeMethod; 3] = [
        RangeMethod::SparseTable,
        RangeMethod::MinMaxMip,
        RangeMethod::BruteForce,
    ];

    /// The kernel's `method` value.
    pub fn code(self) -> u32 {
        match self {
            RangeMethod::SparseTable => 0,
            RangeMethod::MinMaxMip => 1,
            RangeMethod::BruteForce => 2,
        }
    }

    /// A short name for tables.
    pub fn name(self) -> &'static str {
        match self {
            RangeMethod::SparseTable => "sparse table",
            RangeMethod::MinMaxMip => "min–max mip",
            RangeMethod::BruteForce => "brute force",
        }
    }
}

/// A min–max mip on the device: its level 0 (the quantized texels) uploaded, the levels above
/// built by [`GpuMinMaxMip::record_build`].
pub struct GpuMinMaxMip {
    /// All levels, in the layout of [`MinMaxMip::entries`].
    pub entries: GpuBuffer<[u32; 2]>,
    size: usize,
    kernel: std::sync::Arc<Kernel>,
}

impl GpuMinMaxMip {
    /// Allocates the hierarchy of `example` and uploads its quantized texels as level 0 (the
    /// levels above hold nothing until [`GpuMinMaxMip::record_build`] runs).
    ///
    /// # Errors
    /// Allocation, upload and kernel errors.
    pub fn new(gpu: &Gpu, example: &NormalExample) -> GpuResult<Self> {
        let size = example.size();
        let mut entries =
            GpuBuffer::<[u32; 2]>::new(gpu, "glint min-max mip", MinMaxMip::entry_count(size))?;
        entries.write(0, &quantize_texels(example))?;
        Ok(GpuMinMaxMip {
            entries,
            size,
            kernel: gpu.kernel(&GLINT_MINMAX_MIP)?,
        })
    }

    /// Uploads `example` and builds every level (one submission).
    ///
    /// # Errors
    /// As [`GpuMinMaxMip::new`] and dispatch errors.
    pub fn build(gpu: &Gpu, example: &NormalExample) -> GpuResult<Self> {
        let mip = Self::new(gpu, example)?;
        gpu.submit(|rec| mip.record_build(rec))?;
        Ok(mip)
    }

    /// Records the dispatches of levels 1 to log2(size), each from the one below.
    ///
    /// # Errors
    /// Dispatch errors.
    pub fn record_build(&self, rec: &mut Recorder<'_>) -> GpuResult<()> {
        let levels = self.size.trailing_zeros() as usize + 1;
        for m in 1..levels {
            let edge = self.size >> m;
            let push = GlintMinMaxMipPush {
                src: self
                    .entries
                    .address_at(mip_level_offset(self.size, m - 1))?,
                dst: self.entries.address_at(mip_level_offset(self.size, m))?,
                edge: edge as u32,
            };
            if m > 1 {
                rec.barrier();
            }
            rec.dispatch(
                &self.kernel,
                self.kernel.groups_for((edge * edge) as u64),
                &[],
                &push,
            )?;
        }
        Ok(())
    }

    /// Example edge.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The whole hierarchy read back.
    ///
    /// # Errors
    /// Read-back errors.
    pub fn to_host(&self) -> GpuResult<MinMaxMip> {
        Ok(MinMaxMip::from_entries(self.size, self.entries.read()?))
    }
}

/// Records one batch of range queries: `squares[i]` answered by `method` into `results[i]`.
/// `structure` is the sparse table (levels × size² entries, every square's level stored),
/// the full min–max mip, or the quantized texels (size² entries, or the mip, whose level 0
/// they are), by `method`; `kernel` is [`GLINT_RANGE_QUERY`] (see [`range_query_kernel`]).
///
/// # Errors
/// Dispatch errors, and buffers too small for the batch.
#[allow(clippy::too_many_arguments)]
pub fn record_range_queries(
    rec: &mut Recorder<'_>,
    kernel: &Kernel,
    method: RangeMethod,
    structure: &GpuBuffer<[u32; 2]>,
    size: usize,
    squares: &GpuBuffer<RangeSquare>,
    results: &GpuBuffer<[u32; 2]>,
    count: usize,
) -> GpuResult<()> {
    let least = match method {
        RangeMethod::SparseTable => size * size,
        RangeMethod::MinMaxMip => MinMaxMip::entry_count(size),
        RangeMethod::BruteForce => size * size,
    };
    if squares.len() < count || results.len() < count || structure.len() < least {
        return Err(GpuError::InvalidArgument(format!(
            "{} queries over {size}²: {} squares, {} results and {} entries given, {count}, \
             {count} and at least {least} needed",
            method.name(),
            squares.len(),
            results.len(),
            structure.len()
        )));
    }
    let push = GlintRangeQueryPush {
        structure: structure.address(),
        squares: squares.address(),
        results: results.address(),
        count: count as u32,
        size: size as u32,
        method: method.code(),
    };
    rec.dispatch(kernel, kernel.groups_for(count as u64), &[], &push)
}

/// The query kernel of [`record_range_queries`].
///
/// # Errors
/// Kernel creation errors.
pub fn range_query_kernel(gpu: &Gpu) -> GpuResult<std::sync::Arc<Kernel>> {
    gpu.kernel(&GLINT_RANGE_QUERY)
}
