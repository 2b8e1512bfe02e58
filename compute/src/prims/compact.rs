//! Order-preserving stream compaction of `u32` elements: mark, scan, scatter.

use super::push::{CompactMarkPush, CompactScatterPush};
use super::scan::Scan;
use super::{check_aligned, check_len};
use crate::gpu::{Gpu, GpuBuffer, GpuError, GpuResult, Kernel, Recorder};
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

/// GPU stream compaction; keeps its scratch between calls.
pub struct Compactor {
    gpu: Gpu,
    mark: Kernel,
    scatter: Kernel,
    scan: Scan,
    offsets: Option<GpuBuffer<u32>>,
}

impl Compactor {
    /// Builds the kernels.
    pub fn new(gpu: &Gpu) -> GpuResult<Compactor> {
        Ok(Compactor {
            gpu: gpu.clone(),
            mark: Kernel::new(gpu, &prims::COMPACT_MARK)?,
            scatter: Kernel::new(gpu, &prims::COMPACT_SCATTER)?,
            scan: Scan::new(gpu)?,
            offsets: None,
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
            check_aligned(v.name(), v.address())?;
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
        if self.offsets.as_ref().is_none_or(|o| o.len() < n) {
            self.offsets = Some(GpuBuffer::new(&self.gpu, "compaction offsets", n)?);
        }
        let offsets = self.offsets.as_ref().unwrap();
        let (mode, flags, sentinel) = match keep {
            Keep::Flags(f) => (COMPACT_BY_FLAGS, f.address(), 0),
            Keep::NotEqual(s) => (COMPACT_BY_SENTINEL, 0, s),
        };
        let values_addr = values.map_or(0, |v| v.address());
        let groups = self.mark.groups_for(n as u64);
        rec.dispatch(
            &self.mark,
            groups,
            &[],
            &CompactMarkPush {
                values: values_addr,
                flags,
                marks: offsets.address(),
                n: n as u32,
                mode,
                sentinel,
            },
        )?;
        self.scan.record(rec, offsets, offsets, n, Some(count))?;
        let push = CompactScatterPush {
            values: values_addr,
            flags,
            offsets: offsets.address(),
            dst: dst.address(),
            n: n as u32,
            mode,
            sentinel,
            write_indices: (output == CompactOutput::Indices) as u32,
        };
        rec.dispatch(&self.scatter, self.scatter.groups_for(n as u64), &[], &push)
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
