//! Push-constant blocks of the primitive kernels (declared with `push_block!`, so their
//! fields are checked against the reflected GLSL blocks).

use crate::gpu::DeviceAddress;

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct CompactCountPush {
        pub n: u32,
        pub seg_len: u32,
        pub first_segment: u32,
        pub mode: u32,
        pub sentinel: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct CompactWritePush<'a> {
        pub dst: DeviceAddress<'a>,
        pub trash: DeviceAddress<'a>,
        pub n: u32,
        pub seg_len: u32,
        pub first_segment: u32,
        pub first_index: u32,
        pub mode: u32,
        pub sentinel: u32,
        pub write_indices: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct RadixCountPush<'a> {
        pub keys: DeviceAddress<'a>,
        pub hist: DeviceAddress<'a>,
        pub n_at: DeviceAddress<'a>,
        pub hist_n: DeviceAddress<'a>,
        pub n: u32,
        pub seg_len: u32,
        pub threads: u32,
        pub shift: u32,
        pub digit_mask: u32,
        pub key64: u32,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct RadixScatterPush<'a> {
        pub keys_in: DeviceAddress<'a>,
        pub keys_out: DeviceAddress<'a>,
        pub vals_in: DeviceAddress<'a>,
        pub vals_out: DeviceAddress<'a>,
        pub hist: DeviceAddress<'a>,
        pub n_at: DeviceAddress<'a>,
        pub n: u32,
        pub seg_len: u32,
        pub threads: u32,
        pub shift: u32,
        pub digit_mask: u32,
        pub key64: u32,
    }
}

crate::push_block! {
    /// Push block of `copy_vec4.comp`, public for the bandwidth reference in `bench prims`.
    #[derive(Clone, Copy)]
    pub struct CopyPush<'a> {
        /// Source device address.
        pub src: DeviceAddress<'a>,
        /// Destination device address.
        pub dst: DeviceAddress<'a>,
        /// Words to copy.
        pub n: u32,
    }
}

crate::push_block! {
    /// Push block of `copy_words.comp` and `copy_quads.comp` (the descriptor-bound copies),
    /// public for `bench prims` and the core tests.
    #[derive(Clone, Copy)]
    pub struct CopyCountPush {
        /// Elements to copy.
        pub n: u32,
    }
}
