//! Exclusive prefix sum of `u32` (wrapping), by segments: segment totals, a recursive scan of
//! those totals, then every segment scanned from its carry.

use super::check_len;
use super::scratch::grown_level;
use super::segments::{reduce_segments, ScanPush, Split};
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult, Recorder};
use crate::kernels::prims;
use crate::shader_constants::{DEFAULT_WORKGROUP_SIZE, REDUCE_OP_SUM};

/// Plain-Rust reference: exclusive prefix sums (wrapping) and the total.
pub fn exclusive_scan_cpu(input: &[u32]) -> (Vec<u32>, u32) {
    let mut running = 0u32;
    let out = input
        .iter()
        .map(|&v| {
            let before = running;
            running = running.wrapping_add(v);
            before
        })
        .collect();
    (out, running)
}

/// GPU exclusive scan. Keeps its scratch (one buffer per recursion level) between calls; its
/// kernels come from the device's kernel cache when it records.
pub struct Scan {
    gpu: Gpu,
    levels: Vec<GpuBuffer<u32>>,
    /// Words per invocation; `None` picks by device type (long on CPU devices, 16 on GPUs).
    /// Set it to test or tune the other policy.
    pub segment_length: Option<usize>,
    unused_total: GpuBuffer<u32>,
}

impl Scan {
    /// A scan for `gpu`, without scratch yet.
    pub fn new(gpu: &Gpu) -> GpuResult<Scan> {
        Ok(Scan {
            gpu: gpu.clone(),
            levels: Vec::new(),
            segment_length: None,
            unused_total: GpuBuffer::new(gpu, "scan total (unused)", 1)?,
        })
    }

    /// Records the exclusive scan of `src[..n]` into `dst[..n]` (`dst` may be `src`); when
    /// `total` is given, its element 0 receives the sum of all `n` words.
    pub fn record(
        &mut self,
        rec: &mut Recorder<'_>,
        src: &GpuBuffer<u32>,
        dst: &GpuBuffer<u32>,
        n: usize,
        total: Option<&GpuBuffer<u32>>,
    ) -> GpuResult<()> {
        check_len(&format!("scan of {:?}", src.name()), n, src.len())?;
        check_len(&format!("scan into {:?}", dst.name()), n, dst.len())?;
        if let Some(t) = total {
            check_len(&format!("scan total {:?}", t.name()), 1, t.len())?;
        }
        if n == 0 {
            if let Some(t) = total {
                rec.fill(t, 0);
            }
            return Ok(());
        }
        self.reserve(n)?;
        self.record_level(rec, 0, (src, dst), (n, 0), total)
    }

    /// Records the exclusive scan of the first `count` words of `src[..cap]` into `dst`, where
    /// `count` is the word at `count_at`, written on the device by earlier work of the same
    /// submission (at most `cap`; the host never reads it); `total`, when given, receives their
    /// sum (0 for none). The work follows the count, not `cap`: for pipelines that keep their
    /// lengths on the device.
    ///
    /// # Errors
    /// As [`Scan::record`], and a `cap` past one binding's range.
    pub fn record_counted(
        &mut self,
        rec: &mut Recorder<'_>,
        src: &GpuBuffer<u32>,
        dst: &GpuBuffer<u32>,
        cap: usize,
        count_at: DeviceAddress<'_>,
        total: Option<&GpuBuffer<u32>>,
    ) -> GpuResult<()> {
        check_len(&format!("scan of {:?}", src.name()), cap, src.len())?;
        check_len(&format!("scan into {:?}", dst.name()), cap, dst.len())?;
        let split = Split::new(cap.max(1), self.gpu.info(), self.segment_length);
        if split.chunks().count() > 1 {
            return Err(GpuError::InvalidArgument(format!(
                "counted scan of {:?}: {cap} words pass one binding ({} words)",
                src.name(),
                split.chunk
            )));
        }
        self.reserve(cap.max(1))?;
        self.record_level(rec, 0, (src, dst), (cap.max(1), count_at.raw()), total)
    }

    /// Allocates the per-level segment totals that a scan of `n` words needs.
    fn reserve(&mut self, n: usize) -> GpuResult<()> {
        let mut split = Split::new(n, self.gpu.info(), self.segment_length);
        let mut level = 0;
        while split.segments > 1 {
            grown_level(
                &mut self.levels,
                &self.gpu,
                "scan segment totals",
                level,
                split.segments,
            )?;
            split = Split::new(split.segments, self.gpu.info(), self.segment_length);
            level += 1;
        }
        Ok(())
    }

    fn record_level(
        &self,
        rec: &mut Recorder<'_>,
        level: usize,
        (src, dst): (&GpuBuffer<u32>, &GpuBuffer<u32>),
        (n, n_at): (usize, u64),
        total: Option<&GpuBuffer<u32>>,
    ) -> GpuResult<()> {
        let split = Split::new(n, self.gpu.info(), self.segment_length);
        let scan = self.gpu.kernel(&prims::SCAN_SEGMENTS)?;
        let carries = if split.segments > 1 {
            let totals = &self.levels[level];
            let reduce = self.gpu.kernel_with(
                &prims::REDUCE_SEGMENTS,
                DEFAULT_WORKGROUP_SIZE,
                &[(1, REDUCE_OP_SUM)],
            )?;
            reduce_segments(rec, &reduce, src, &split, totals, n_at)?;
            // Past a device count, segment totals are stale; only the carries of the segments
            // below it are used, and they sum the totals before them.
            self.record_level(rec, level + 1, (totals, totals), (split.segments, 0), None)?;
            Some(totals)
        } else {
            None
        };
        let total_buffer = total.unwrap_or(&self.unused_total);
        for (first, words) in split.chunks() {
            let push = ScanPush {
                n_at,
                n: words as u32,
                seg_len: split.seg_len as u32,
                first_segment: (first / split.seg_len) as u32,
                has_carries: carries.is_some() as u32,
                write_total: (total.is_some() && first + words == n) as u32,
            };
            let out = dst.arg_range(first, words)?;
            let bindings = [
                ("Src", src.arg_range(first, words)?),
                ("Dst", out),
                ("DstWords", out),
                ("Carries", carries.unwrap_or(total_buffer).arg()),
                ("Total", total_buffer.arg()),
            ];
            rec.dispatch(&scan, split.groups(&scan, words), &bindings, &push)?;
        }
        Ok(())
    }

    /// Scans `input` on the GPU and reads the result back: `(prefix sums, total)`.
    pub fn run(&mut self, input: &[u32]) -> GpuResult<(Vec<u32>, u32)> {
        let gpu = self.gpu.clone();
        let buf = GpuBuffer::from_slice(&gpu, "scan input", input)?;
        let total = GpuBuffer::<u32>::new(&gpu, "scan total", 1)?;
        gpu.submit(|rec| self.record(rec, &buf, &buf, input.len(), Some(&total)))?;
        Ok((buf.read()?, total.read()?[0]))
    }
}
