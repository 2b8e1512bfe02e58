//! Scratch buffers that primitives keep between calls and grow on demand.

use crate::gpu::{Gpu, GpuBuffer, GpuResult};
use bytemuck::Pod;

/// The buffer in `slot`, replaced by a new one of `len` elements when absent or shorter.
pub(crate) fn grown<'a, T: Pod>(
    slot: &'a mut Option<GpuBuffer<T>>,
    gpu: &Gpu,
    name: &str,
    len: usize,
) -> GpuResult<&'a GpuBuffer<T>> {
    if slot.as_ref().is_none_or(|b| b.len() < len) {
        *slot = Some(GpuBuffer::new(gpu, name, len)?);
    }
    Ok(slot.as_ref().expect("just filled"))
}

/// Level `level` of a per-level scratch list, grown (or appended) to hold `len` elements.
pub(crate) fn grown_level<T: Pod>(
    levels: &mut Vec<GpuBuffer<T>>,
    gpu: &Gpu,
    name: &str,
    level: usize,
    len: usize,
) -> GpuResult<()> {
    if levels.get(level).is_none_or(|b| b.len() < len) {
        let buffer = GpuBuffer::new(gpu, format!("{name} (level {level})"), len)?;
        if level < levels.len() {
            levels[level] = buffer;
        } else {
            levels.push(buffer);
        }
    }
    Ok(())
}
