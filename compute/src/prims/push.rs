//! Push-constant blocks of the primitive kernels. Layouts follow GLSL's scalar layout: 64-bit
//! fields first, so `packed(4)` reproduces the GLSL offsets; sizes are checked against the
//! reflected blocks at every dispatch.

use bytemuck::{Pod, Zeroable};

#[derive(Clone, Copy, Pod, Zeroable)]
#[repr(C)]
pub(crate) struct CompactCountPush {
    pub n: u32,
    pub seg_len: u32,
    pub first_segment: u32,
    pub mode: u32,
    pub sentinel: u32,
}

#[derive(Clone, Copy, Pod, Zeroable)]
#[repr(C, packed(4))]
pub(crate) struct CompactWritePush {
    pub dst: u64,
    pub trash: u64,
    pub n: u32,
    pub seg_len: u32,
    pub first_segment: u32,
    pub first_index: u32,
    pub mode: u32,
    pub sentinel: u32,
    pub write_indices: u32,
}

#[derive(Clone, Copy, Pod, Zeroable)]
#[repr(C, packed(4))]
pub(crate) struct RadixCountPush {
    pub keys: u64,
    pub hist: u64,
    pub n: u32,
    pub seg_len: u32,
    pub threads: u32,
    pub shift: u32,
    pub digit_mask: u32,
    pub key64: u32,
}

#[derive(Clone, Copy, Pod, Zeroable)]
#[repr(C, packed(4))]
pub(crate) struct RadixScatterPush {
    pub keys_in: u64,
    pub keys_out: u64,
    pub vals_in: u64,
    pub vals_out: u64,
    pub hist: u64,
    pub n: u32,
    pub seg_len: u32,
    pub threads: u32,
    pub shift: u32,
    pub digit_mask: u32,
    pub key64: u32,
}

/// Push block of `copy_vec4.comp`, public for the bandwidth reference in `bench prims`.
#[derive(Clone, Copy, Pod, Zeroable)]
#[repr(C, packed(4))]
pub struct CopyPush {
    /// Source device address.
    pub src: u64,
    /// Destination device address.
    pub dst: u64,
    /// Words to copy.
    pub n: u32,
}
