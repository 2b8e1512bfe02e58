//! Reduction of `u32` words to one: wrapping sum, minimum or maximum, by repeated tile
//! reductions until one word is left.

use super::check_len;
use super::scratch::grown_level;
use super::segments::{reduce_segments, Split};
use crate::gpu::{Gpu, GpuBuffer, GpuResult, Recorder};
use crate::kernels::prims;
use crate::shader_constants::{
    DEFAULT_WORKGROUP_SIZE, REDUCE_OP_MAX, REDUCE_OP_MIN, REDUCE_OP_SUM,
};

/// The reduction operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReduceOp {
    /// Wrapping sum (modulo 2^32), identity 0.
    Sum,
    /// Minimum, identity `u32::MAX`.
    Min,
    /// Maximum, identity 0.
    Max,
}

impl ReduceOp {
    /// The value an empty input reduces to.
    pub fn identity(self) -> u32 {
        match self {
            ReduceOp::Min => u32::MAX,
            ReduceOp::Sum | ReduceOp::Max => 0,
        }
    }

    /// The `REDUCE_OP_*` specialization constant.
    fn id(self) -> u32 {
        match self {
            ReduceOp::Sum => REDUCE_OP_SUM,
            ReduceOp::Min => REDUCE_OP_MIN,
            ReduceOp::Max => REDUCE_OP_MAX,
        }
    }
}

/// Plain-Rust reference.
pub fn reduce_cpu(input: &[u32], op: ReduceOp) -> u32 {
    match op {
        ReduceOp::Sum => input.iter().fold(0u32, |a, &b| a.wrapping_add(b)),
        ReduceOp::Min => input.iter().copied().min().unwrap_or(u32::MAX),
        ReduceOp::Max => input.iter().copied().max().unwrap_or(0),
    }
}

/// GPU reduction; keeps its scratch between calls.
pub struct Reduce {
    gpu: Gpu,
    levels: Vec<GpuBuffer<u32>>,
    /// Words per invocation; `None` picks by device type (long on CPU devices, 16 on GPUs).
    /// Set it to test or tune the other policy.
    pub segment_length: Option<usize>,
}

impl Reduce {
    /// A reduction for `gpu`, without scratch yet. Its kernel, specialized per operator, comes
    /// from the device's kernel cache when it records.
    pub fn new(gpu: &Gpu) -> GpuResult<Reduce> {
        Ok(Reduce {
            gpu: gpu.clone(),
            levels: Vec::new(),
            segment_length: None,
        })
    }

    /// Records the reduction of `src[..n]` into `result[0]`.
    pub fn record(
        &mut self,
        rec: &mut Recorder<'_>,
        src: &GpuBuffer<u32>,
        n: usize,
        op: ReduceOp,
        result: &GpuBuffer<u32>,
    ) -> GpuResult<()> {
        check_len(&format!("reduce of {:?}", src.name()), n, src.len())?;
        check_len(
            &format!("reduce result {:?}", result.name()),
            1,
            result.len(),
        )?;
        if n == 0 {
            rec.fill(result, op.identity());
            return Ok(());
        }
        if n == 1 {
            return rec.copy(src, 0, result, 0, 1);
        }
        // Level sizes: n -> its segment count -> ... -> 1; intermediate levels live in scratch.
        let mut splits = vec![Split::new(n, self.gpu.info(), self.segment_length)];
        while splits.last().unwrap().segments > 1 {
            splits.push(Split::new(
                splits.last().unwrap().segments,
                self.gpu.info(),
                self.segment_length,
            ));
        }
        let sizes: Vec<usize> = splits.iter().map(|s| s.n).chain([1]).collect();
        for (level, &size) in sizes[1..sizes.len() - 1].iter().enumerate() {
            grown_level(&mut self.levels, &self.gpu, "reduce partials", level, size)?;
        }
        let kernel = self.gpu.kernel_with(
            &prims::REDUCE_SEGMENTS,
            DEFAULT_WORKGROUP_SIZE,
            &[(1, op.id())],
        )?;
        for (i, split) in splits.iter().enumerate() {
            let from = if i == 0 { src } else { &self.levels[i - 1] };
            let to = if i + 1 == splits.len() {
                result
            } else {
                &self.levels[i]
            };
            reduce_segments(rec, &kernel, from, split, to, 0)?;
        }
        Ok(())
    }

    /// Reduces `input` on the GPU and reads the result back.
    pub fn run(&mut self, input: &[u32], op: ReduceOp) -> GpuResult<u32> {
        let gpu = self.gpu.clone();
        let buf = GpuBuffer::from_slice(&gpu, "reduce input", input)?;
        let result = GpuBuffer::<u32>::new(&gpu, "reduce result", 1)?;
        gpu.submit(|rec| self.record(rec, &buf, input.len(), op, &result))?;
        Ok(result.read()?[0])
    }
}
