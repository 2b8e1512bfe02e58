//! GPU primitives that every structure builder uses, each with its plain-Rust reference:
//! exclusive scan, reduce, stream compaction and LSD radix sort.
//!
//! All of them address their data through buffer device addresses, so inputs larger than one
//! storage-buffer binding (128 MiB on lavapipe) need no splitting; element counts are limited to
//! `i32::MAX` (SPIR-V array indices are signed) and buffers to the device's allocation limits.
//! Each primitive records into a caller's [`Recorder`](crate::gpu::Recorder), so several run in
//! one submission, and also offers a one-call convenience that submits and reads back.

mod compact;
pub mod push;
mod radix_sort;
mod reduce;
mod scan;
mod scratch;
pub(crate) mod segments;

pub use compact::{compact_cpu, CompactOutput, Compactor, Keep, KeepCpu};
pub use radix_sort::{sort_pairs_cpu, RadixSort};
pub use reduce::{reduce_cpu, Reduce, ReduceOp};
pub use scan::{exclusive_scan_cpu, Scan};

use crate::gpu::{GpuError, GpuResult};

/// Largest element count a primitive accepts: SPIR-V indices are signed 32-bit.
pub const MAX_ELEMENTS: usize = i32::MAX as usize;

/// Checks that `n` elements are within the primitive limit and the buffer's length.
pub fn check_len(what: &str, n: usize, available: usize) -> GpuResult<()> {
    if n > MAX_ELEMENTS {
        return Err(GpuError::InvalidArgument(format!(
            "{what}: {n} elements exceeds the primitive limit of {MAX_ELEMENTS}"
        )));
    }
    if n > available {
        return Err(GpuError::InvalidArgument(format!(
            "{what}: {n} elements requested but the buffer holds {available}"
        )));
    }
    Ok(())
}

pub(crate) fn check_aligned(what: &str, address: u64) -> GpuResult<()> {
    if address % 16 != 0 {
        return Err(GpuError::InvalidArgument(format!(
            "{what}: device address {address:#x} is not 16-byte aligned"
        )));
    }
    Ok(())
}
