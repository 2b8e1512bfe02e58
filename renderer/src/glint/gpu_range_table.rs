//! The device build of the range table ([`super::range_table`]): bottom-up, one dispatch of
//! `glsl/render/glint_range_level.comp` per level (not the paper's recursion, which recomputes
//! every sub-square), each reading the level below.

use super::example::NormalExample;
use super::range_table::quantize_texels;
use crate::kernels::render::GLINT_RANGE_LEVEL;
use lazysolid_compute::gpu::{
    DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult, Kernel, Recorder,
};

lazysolid_compute::push_block! {
    /// Push block of `glsl/render/glint_range_level.comp`.
    #[derive(Clone, Copy)]
    pub struct GlintRangeLevelPush<'a> {
        /// The level below (or the quantized texels for level 0).
        pub src: DeviceAddress<'a>,
        /// The level written.
        pub dst: DeviceAddress<'a>,
        /// Example edge.
        pub size: u32,
        /// Offset of the 4 entries read: 2^(k−1) (1 for level 0, which reads texels).
        pub offset: u32,
        /// Edge 2^k of the level's squares: starts with x + span > size − 1 stay empty.
        pub span: u32,
    }
}

/// Builds the range table of `example` with levels up to edge `patch` on the device: `levels`
/// × size² packed entries, level by level (the layout of [`super::RangeTable::entries`]).
///
/// # Errors
/// Allocation, upload and dispatch errors.
pub fn build_range_table(
    gpu: &Gpu,
    example: &NormalExample,
    patch: u32,
) -> GpuResult<GpuBuffer<[u32; 2]>> {
    let size = example.size();
    let levels = patch.trailing_zeros() as usize + 1;
    let texels = GpuBuffer::from_slice(gpu, "glint quantized texels", &quantize_texels(example))?;
    let table = GpuBuffer::<[u32; 2]>::new(gpu, "glint range table", levels * size * size)?;
    let kernel = gpu.kernel(&GLINT_RANGE_LEVEL)?;
    gpu.submit(|rec| record_range_table(rec, &kernel, &texels, &table, size, levels))?;
    Ok(table)
}

/// Records the level dispatches of a range table of `levels` levels over the quantized texels
/// `texels` of an example of edge `size` into `table` (`levels` × size² entries); `kernel` is
/// [`GLINT_RANGE_LEVEL`]. The texels must be on the device when the commands run.
///
/// # Errors
/// Dispatch errors, and buffers too small for `size` and `levels`.
pub fn record_range_table(
    rec: &mut Recorder<'_>,
    kernel: &Kernel,
    texels: &GpuBuffer<[u32; 2]>,
    table: &GpuBuffer<[u32; 2]>,
    size: usize,
    levels: usize,
) -> GpuResult<()> {
    let area = size * size;
    if texels.len() < area || table.len() < levels * area {
        return Err(GpuError::InvalidArgument(format!(
            "range table of {levels} levels over {size}²: {} texels and {} entries given, \
             {area} and {} needed",
            texels.len(),
            table.len(),
            levels * area
        )));
    }
    for k in 0..levels {
        let src = if k == 0 {
            texels.address()
        } else {
            table.address_at((k - 1) * area)?
        };
        let push = GlintRangeLevelPush {
            src,
            dst: table.address_at(k * area)?,
            size: size as u32,
            offset: if k == 0 { 1 } else { 1 << (k - 1) },
            span: 1 << k,
        };
        if k > 0 {
            rec.barrier();
        }
        rec.dispatch(kernel, kernel.groups_for(area as u64), &[], &push)?;
    }
    Ok(())
}
