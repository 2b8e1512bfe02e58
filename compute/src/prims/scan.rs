//! Exclusive prefix sum of `u32` (wrapping), reduce-then-scan over tiles of `SCAN_TILE` words:
//! tile totals, a recursive scan of those totals, then each tile scanned with its carry.

use super::push::{ReducePush, ScanPush};
use super::{check_aligned, check_len};
use crate::gpu::{Gpu, GpuBuffer, GpuResult, Kernel, Recorder};
use crate::kernels::prims;
use crate::shader_constants::{REDUCE_OP_SUM, SCAN_TILE};

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

/// GPU exclusive scan. Keeps its scratch (one buffer per recursion level) between calls.
pub struct Scan {
    gpu: Gpu,
    reduce: Kernel,
    scan: Kernel,
    levels: Vec<GpuBuffer<u32>>,
}

impl Scan {
    /// Builds the kernels.
    pub fn new(gpu: &Gpu) -> GpuResult<Scan> {
        Ok(Scan {
            gpu: gpu.clone(),
            reduce: Kernel::with_constants(
                gpu,
                &prims::REDUCE_TILES,
                crate::shader_constants::DEFAULT_WORKGROUP_SIZE,
                &[(1, REDUCE_OP_SUM)],
            )?,
            scan: Kernel::new(gpu, &prims::SCAN_TILES)?,
            levels: Vec::new(),
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
        check_aligned(src.name(), src.address())?;
        check_aligned(dst.name(), dst.address())?;
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
        self.record_level(
            rec,
            0,
            src.address(),
            dst.address(),
            n as u32,
            total.map_or(0, |t| t.address()),
        )
    }

    /// Allocates the per-level tile totals that a scan of `n` words needs.
    fn reserve(&mut self, n: usize) -> GpuResult<()> {
        let mut tiles = n.div_ceil(SCAN_TILE as usize);
        let mut level = 0;
        while tiles > 1 {
            if self.levels.get(level).is_none_or(|b| b.len() < tiles) {
                let buffer = GpuBuffer::new(
                    &self.gpu,
                    format!("scan tile totals (level {level})"),
                    tiles,
                )?;
                if level < self.levels.len() {
                    self.levels[level] = buffer;
                } else {
                    self.levels.push(buffer);
                }
            }
            tiles = tiles.div_ceil(SCAN_TILE as usize);
            level += 1;
        }
        Ok(())
    }

    fn record_level(
        &self,
        rec: &mut Recorder<'_>,
        level: usize,
        src: u64,
        dst: u64,
        n: u32,
        total: u64,
    ) -> GpuResult<()> {
        let tiles = n.div_ceil(SCAN_TILE) as u64;
        let mut carries = 0;
        if tiles > 1 {
            carries = self.levels[level].address();
            rec.dispatch(
                &self.reduce,
                self.reduce.groups(tiles),
                &[],
                &ReducePush {
                    src,
                    dst: carries,
                    n,
                },
            )?;
            self.record_level(rec, level + 1, carries, carries, tiles as u32, 0)?;
        }
        rec.dispatch(
            &self.scan,
            self.scan.groups(tiles),
            &[],
            &ScanPush {
                src,
                dst,
                carries,
                total,
                n,
            },
        )
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
