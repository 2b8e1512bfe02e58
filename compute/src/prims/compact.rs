//! Order-preserving stream compaction of `u32` elements by segments: every invocation counts the
//! kept words of its segment, a scan turns the counts into output offsets, and every invocation
//! writes its kept words contiguously from its offset.

use super::check_len;
use super::push::{CompactCountPush, CompactWritePush};
use super::scan::Scan;
use super::scratch::grown;
use super::segments::Split;
use crate::gpu::{Gpu, GpuBuffer, GpuError, GpuResult, Recorder};
use crate::kernels::prims;
use crate::shader_constants::{COMPACT_BY_FLAGS, COMPACT_BY_SENTINEL};

/// Which elements survive.
#[derive(Clone, Copy)]
pub enum Keep<'a> {
    /// Element `i` is kept where `flags[i] != 0`.
    Flags(&'a GpuBuffer<u32>),
    /// Element `i` is kept where `values[i] != sentinel`.
    NotEqual(u32),
}

/// [`Keep`] for the CPU reference.
#[derive(Clone, Copy)]
pub enum KeepCpu<'a> {
    /// See [`Keep::Flags`].
    Flags(&'a [u32]),
    /// See [`Keep::NotEqual`].
    NotEqual(u32),
}

/// What a kept element writes to the output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompactOutput {
    /// The element's value.
    Values,
    /// The element's index in the input (the "which ones" list that builders need).
    Indices,
}

/// Plain-Rust reference: the kept values or indices, in input order.
pub fn compact_cpu(values: &[u32], keep: KeepCpu<'_>, output: CompactOutput) -> Vec<u32> {
    (0..values.len())
        .filter(|&i| match keep {
            KeepCpu::Flags(f) => f[i] != 0,
            KeepCpu::NotEqual(s) => values[i] != s,
        })
        .map(|i| {
            if output == CompactOutput::Indices {
                i as u32
            } else {
                values[i]
            }
        })
        .collect()
}

/// GPU stream compaction; keeps its scratch between calls. Its kernels come from the device's
/// kernel cache when it records.
pub struct Compactor {
    gpu: Gpu,
    scan: Scan,
    offsets: Option<GpuBuffer<u32>>,
    trash: GpuBuffer<u32>,
    /// Words per invocation; `None` picks by device type (as for [`Scan`]).
    pub segment_length: Option<usize>,
}

impl Compactor {
    /// A compactor for `gpu`, with its one-word trash buffer.
    pub fn new(gpu: &Gpu) -> GpuResult<Compactor> {
        Ok(Compactor {
            gpu: gpu.clone(),
            scan: Scan::new(gpu)?,
            offsets: None,
            trash: GpuBuffer::new(gpu, "compaction trash word", 1)?,
            segment_length: None,
        })
    }

    /// Records the compaction of the first `n` elements of `values` into `dst`, and the number
    /// kept into `count[0]`. `values` may be `None` only with [`Keep::Flags`] and
    /// [`CompactOutput::Indices`]. `dst` must hold `n` elements (the worst case).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        rec: &mut Recorder<'_>,
        values: Option<&GpuBuffer<u32>>,
        keep: Keep<'_>,
        n: usize,
        output: CompactOutput,
        dst: &GpuBuffer<u32>,
        count: &GpuBuffer<u32>,
    ) -> GpuResult<()> {
        if let Some(v) = values {
            check_len(&format!("compaction of {:?}", v.name()), n, v.len())?;
        } else if matches!(keep, Keep::NotEqual(_)) || output == CompactOutput::Values {
            return Err(GpuError::InvalidArgument(
                "compaction without a values buffer needs Keep::Flags and CompactOutput::Indices"
                    .into(),
            ));
        }
        if let Keep::Flags(f) = keep {
            check_len(&format!("compaction flags {:?}", f.name()), n, f.len())?;
        }
        check_len(&format!("compaction output {:?}", dst.name()), n, dst.len())?;
        check_len(
            &format!("compaction count {:?}", count.name()),
            1,
            count.len(),
        )?;
        if n == 0 {
            rec.fill(count, 0);
            return Ok(());
        }
        let count_kernel = self.gpu.kernel(&prims::COMPACT_COUNT)?;
        let write_kernel = self.gpu.kernel(&prims::COMPACT_WRITE)?;
        let split = Split::new(n, self.gpu.info(), self.segment_length);
        let offsets = grown(
            &mut self.offsets,
            &self.gpu,
            "compaction segment offsets",
            split.segments,
        )?;
        // The kernels always read both a value and a flag stream; bind what stands in for the
        // one that is not used.
        let (mode, flags, sentinel) = match keep {
            Keep::Flags(f) => (COMPACT_BY_FLAGS, f, 0),
            Keep::NotEqual(s) => (COMPACT_BY_SENTINEL, values.expect("checked above"), s),
        };
        let values = values.unwrap_or(flags);
        for (first, words) in split.chunks() {
            let first_segment = (first / split.seg_len) as u32;
            let push = CompactCountPush {
                n: words as u32,
                seg_len: split.seg_len as u32,
                first_segment,
                mode,
                sentinel,
            };
            let bindings = [
                ("Src", values.arg_range(first, words)?),
                ("Flags", flags.arg_range(first, words)?),
                ("Counts", offsets.arg()),
            ];
            rec.dispatch(
                &count_kernel,
                split.groups(&count_kernel, words),
                &bindings,
                &push,
            )?;
        }
        self.scan
            .record(rec, offsets, offsets, split.segments, Some(count))?;
        for (first, words) in split.chunks() {
            let push = CompactWritePush {
                dst: dst.address(),
                trash: self.trash.address(),
                n: words as u32,
                seg_len: split.seg_len as u32,
                first_segment: (first / split.seg_len) as u32,
                first_index: first as u32,
                mode,
                sentinel,
                write_indices: (output == CompactOutput::Indices) as u32,
            };
            let bindings = [
                ("Src", values.arg_range(first, words)?),
                ("Flags", flags.arg_range(first, words)?),
                ("Offsets", offsets.arg()),
            ];
            rec.dispatch(
                &write_kernel,
                split.groups(&write_kernel, words),
                &bindings,
                &push,
            )?;
        }
        Ok(())
    }

    /// Compacts `values` on the GPU and reads the kept elements back.
    pub fn run(
        &mut self,
        values: &[u32],
        keep: KeepCpu<'_>,
        output: CompactOutput,
    ) -> GpuResult<Vec<u32>> {
        let gpu = self.gpu.clone();
        let v = GpuBuffer::from_slice(&gpu, "compaction values", values)?;
        let flags = match keep {
            KeepCpu::Flags(f) => Some(GpuBuffer::from_slice(&gpu, "compaction flags", f)?),
            KeepCpu::NotEqual(_) => None,
        };
        let keep = match (keep, &flags) {
            (KeepCpu::Flags(_), Some(f)) => Keep::Flags(f),
            (KeepCpu::NotEqual(s), _) => Keep::NotEqual(s),
            _ => unreachable!(),
        };
        let dst = GpuBuffer::<u32>::new(&gpu, "compaction output", values.len())?;
        let count = GpuBuffer::<u32>::new(&gpu, "compaction count", 1)?;
        gpu.submit(|rec| self.record(rec, Some(&v), keep, values.len(), output, &dst, &count))?;
        let kept = count.read()?[0] as usize;
        dst.read_range(0, kept)
    }
}
