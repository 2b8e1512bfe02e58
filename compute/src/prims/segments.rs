//! How scan and reduce split their input: into per-invocation segments (see
//! `glsl/include/segments.glsl`), grouped into chunks that one descriptor binding can cover.

use crate::gpu::{DeviceInfo, GpuBuffer, GpuResult, Kernel, Recorder};

crate::push_block! {
    /// Push block of `reduce_segments.comp`.
    #[derive(Clone, Copy)]
    pub(crate) struct ReducePush {
        pub n_at: u64,
        pub n: u32,
        pub seg_len: u32,
        pub first_segment: u32,
    }
}

crate::push_block! {
    /// Push block of `scan_segments.comp`.
    #[derive(Clone, Copy)]
    pub(crate) struct ScanPush {
        pub n_at: u64,
        pub n: u32,
        pub seg_len: u32,
        pub first_segment: u32,
        pub has_carries: u32,
        pub write_total: u32,
    }
}

/// Words a CPU device scans or reduces in one invocation rather than splitting them: each
/// dispatch costs lavapipe about 0.1 ms whatever its size, more than one lane's pass over
/// this many words, and larger inputs get at most this many segments, so that the segment
/// totals take one invocation in turn (a scan is 1 or 3 dispatches, not up to 7).
pub(crate) const CPU_SINGLE_SEGMENT: usize = 4096;

/// The split of `n` words: segment length (a multiple of 4), number of segments and words per
/// bound chunk (a multiple of the segment length).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Split {
    pub n: usize,
    pub seg_len: usize,
    pub segments: usize,
    pub chunk: usize,
}

impl Split {
    /// On a CPU device, long segments: each invocation streams through memory like a CPU
    /// thread, at most [`CPU_SINGLE_SEGMENT`] of them (16 workgroups, enough to balance the
    /// driver's threads), and small inputs in a single segment. On a GPU,
    /// short segments, so neighbouring invocations read neighbouring quads.
    pub fn new(n: usize, device: &DeviceInfo, forced: Option<usize>) -> Split {
        let seg_len = if let Some(len) = forced {
            len.next_multiple_of(4).max(4)
        } else if device.device_type == "cpu" {
            if n <= CPU_SINGLE_SEGMENT {
                n.next_multiple_of(4).max(4)
            } else {
                n.div_ceil(CPU_SINGLE_SEGMENT)
                    .next_multiple_of(4)
                    .clamp(16, 1 << 16)
            }
        } else {
            16
        };
        let words_per_binding = (device.max_storage_buffer_range / 4) as usize;
        let chunk = (words_per_binding / seg_len).max(1) * seg_len;
        Split {
            n,
            seg_len,
            segments: n.div_ceil(seg_len),
            chunk: chunk.min(super::MAX_ELEMENTS / seg_len * seg_len),
        }
    }

    /// `(first word, words)` of every chunk.
    pub fn chunks(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.n)
            .step_by(self.chunk)
            .map(move |first| (first, self.chunk.min(self.n - first)))
    }

    /// Workgroups for the segments of one chunk of `words`.
    pub fn groups(&self, kernel: &Kernel, words: usize) -> [u32; 3] {
        kernel.groups_for(words.div_ceil(self.seg_len) as u64)
    }
}

/// Records the reduction of every segment of `src[..split.n]` into `dst[segment]` (of the
/// segments below the length at device address `n_at` when it is not 0).
pub(crate) fn reduce_segments(
    rec: &mut Recorder<'_>,
    kernel: &Kernel,
    src: &GpuBuffer<u32>,
    split: &Split,
    dst: &GpuBuffer<u32>,
    n_at: u64,
) -> GpuResult<()> {
    for (first, words) in split.chunks() {
        let push = ReducePush {
            n_at,
            n: words as u32,
            seg_len: split.seg_len as u32,
            first_segment: (first / split.seg_len) as u32,
        };
        rec.dispatch(
            kernel,
            split.groups(kernel, words),
            &[("Src", src.arg_range(first, words)?), ("Dst", dst.arg())],
            &push,
        )?;
    }
    Ok(())
}
