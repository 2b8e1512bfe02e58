//! Stable LSD radix sort on the GPU, `RADIX_BITS` per pass: `u32` keys, or `u64` keys, each
//! optionally carrying a `u32` value.
//!
//! Each pass: every invocation counts the digits of its own contiguous segment into its column
//! of a digit-major histogram (no atomics), one exclusive scan of that histogram gives every
//! (digit, invocation) pair its output offset, and every invocation scatters its segment in
//! order. Segments in order and offsets ordered by (digit, invocation) make each pass stable.

use super::push::{RadixCountPush, RadixScatterPush};
use super::scan::Scan;
use super::scratch::grown;
use super::{check_aligned, check_len};
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuError, GpuResult, Kernel, Recorder};
use crate::kernels::prims;
use crate::shader_constants::{
    DEFAULT_WORKGROUP_SIZE, RADIX_BITS, RADIX_BUCKETS, RADIX_KEYS_PER_INVOCATION,
};
use bytemuck::Pod;

/// Plain-Rust reference: a stable sort of `(key, value)` pairs by the low `key_bits` bits of the
/// key (what the GPU sort computes).
pub fn sort_pairs_cpu<K: Copy + Into<u64>, V: Copy>(
    keys: &[K],
    values: &[V],
    key_bits: u32,
) -> (Vec<K>, Vec<V>) {
    let mask = if key_bits >= 64 {
        u64::MAX
    } else {
        (1u64 << key_bits) - 1
    };
    let mut order: Vec<usize> = (0..keys.len()).collect();
    order.sort_by_key(|&i| keys[i].into() & mask);
    (
        order.iter().map(|&i| keys[i]).collect(),
        order.iter().map(|&i| values[i]).collect(),
    )
}

/// GPU radix sort; keeps its scratch between calls. Its kernels come from the device's kernel
/// cache when it records.
pub struct RadixSort {
    gpu: Gpu,
    scan: Scan,
    hist: Option<GpuBuffer<u32>>,
    keys32: Option<GpuBuffer<u32>>,
    keys64: Option<GpuBuffer<u64>>,
    values: Option<GpuBuffer<u32>>,
    /// The histogram's length of a counted sort, written by its count kernel for its scan.
    hist_n: GpuBuffer<u32>,
    /// Most invocations a pass uses; each owns a segment of `n / threads` keys.
    pub max_threads: u32,
}

struct Job<'a> {
    keys: (DeviceAddress<'a>, DeviceAddress<'a>),
    values: Option<(DeviceAddress<'a>, DeviceAddress<'a>)>,
    n: u32,
    /// Not null: the key count, at most `n`, read on the device.
    n_at: DeviceAddress<'a>,
    key64: bool,
    key_bits: u32,
    threads: u32,
}

impl RadixSort {
    /// A sort for `gpu`, without scratch yet.
    pub fn new(gpu: &Gpu) -> GpuResult<RadixSort> {
        Ok(RadixSort {
            gpu: gpu.clone(),
            scan: Scan::new(gpu)?,
            hist: None,
            keys32: None,
            keys64: None,
            values: None,
            hist_n: GpuBuffer::zeroed(gpu, "radix sort histogram length", 1)?,
            max_threads: 2048,
        })
    }

    /// Records an in-place sort of `keys[..n]` by their low `key_bits` bits (1..=32).
    pub fn record_u32(
        &mut self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u32>,
        n: usize,
        key_bits: u32,
    ) -> GpuResult<()> {
        self.record_any(rec, keys, None, (n, None), key_bits, 32)
    }

    /// Records an in-place sort of `keys[..n]` by their low `key_bits` bits (1..=32), moving
    /// `values[..n]` along.
    pub fn record_u32_pairs(
        &mut self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u32>,
        values: &GpuBuffer<u32>,
        n: usize,
        key_bits: u32,
    ) -> GpuResult<()> {
        self.record_any(rec, keys, Some(values), (n, None), key_bits, 32)
    }

    /// Records an in-place sort of `u64` `keys[..n]` by their low `key_bits` bits (1..=64),
    /// moving `values[..n]` along when given.
    pub fn record_u64(
        &mut self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        values: Option<&GpuBuffer<u32>>,
        n: usize,
        key_bits: u32,
    ) -> GpuResult<()> {
        self.record_any(rec, keys, values, (n, None), key_bits, 64)
    }

    /// Records an in-place sort of the first `count` `u64` keys of `keys[..cap]` by their low
    /// `key_bits` bits, where `count` is the word at `count_at`, written on the device by
    /// earlier work of the same submission (at most `cap`; the host never reads it). For
    /// pipelines that keep their lengths on the device: the passes are sized for `cap`, each
    /// invocation's segment for the count.
    ///
    /// # Errors
    /// As [`RadixSort::record_u64`].
    pub fn record_u64_counted(
        &mut self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<u64>,
        cap: usize,
        count_at: DeviceAddress<'_>,
        key_bits: u32,
    ) -> GpuResult<()> {
        self.record_any(rec, keys, None, (cap, Some(count_at)), key_bits, 64)
    }

    fn record_any<K: Pod>(
        &mut self,
        rec: &mut Recorder<'_>,
        keys: &GpuBuffer<K>,
        values: Option<&GpuBuffer<u32>>,
        (n, n_at): (usize, Option<DeviceAddress<'_>>),
        key_bits: u32,
        width: u32,
    ) -> GpuResult<()> {
        if key_bits == 0 || key_bits > width {
            return Err(GpuError::InvalidArgument(format!(
                "radix sort of {:?}: key_bits {key_bits} is outside 1..={width}",
                keys.name()
            )));
        }
        check_len(&format!("radix sort of {:?}", keys.name()), n, keys.len())?;
        check_aligned(keys.name(), keys.address().raw())?;
        if let Some(v) = values {
            check_len(&format!("radix sort values {:?}", v.name()), n, v.len())?;
        }
        if n <= 1 {
            return Ok(());
        }
        let key64 = width == 64;
        if key64 {
            grown(
                &mut self.keys64,
                &self.gpu,
                "radix sort scratch keys (u64)",
                n,
            )?;
        } else {
            grown(
                &mut self.keys32,
                &self.gpu,
                "radix sort scratch keys (u32)",
                n,
            )?;
        }
        if values.is_some() {
            grown(&mut self.values, &self.gpu, "radix sort scratch values", n)?;
        }
        let threads = self.threads_for(n as u32);
        let hist_len = (RADIX_BUCKETS * threads) as usize;
        grown(&mut self.hist, &self.gpu, "radix sort histogram", hist_len)?;
        let scratch_keys = if key64 {
            self.keys64.as_ref().map(GpuBuffer::address)
        } else {
            self.keys32.as_ref().map(GpuBuffer::address)
        }
        .expect("grown above");
        let scratch_values = self.values.as_ref().filter(|_| values.is_some());
        let job = Job {
            keys: (keys.address(), scratch_keys),
            values: values
                .zip(scratch_values)
                .map(|(v, s)| (v.address(), s.address())),
            n: n as u32,
            n_at: n_at.unwrap_or(DeviceAddress::NULL),
            key64,
            key_bits,
            threads,
        };
        let passes = key_bits.div_ceil(RADIX_BITS);
        let hist = self.hist.as_ref().expect("grown above");
        let count = self.gpu.kernel(&prims::RADIX_COUNT)?;
        let scatter = self.gpu.kernel(&prims::RADIX_SCATTER)?;
        record_passes(
            rec,
            [&count, &scatter],
            &mut self.scan,
            (hist, &self.hist_n),
            &job,
        )?;
        if passes % 2 == 1 {
            // The result sits in the scratch buffers: copy it home.
            let bytes = keys.bytes().min((n * size_of::<K>()) as u64);
            if key64 {
                rec.copy_bytes(self.keys64.as_ref().expect("grown above"), keys, bytes);
            } else {
                rec.copy_bytes(self.keys32.as_ref().expect("grown above"), keys, bytes);
            }
            if let (Some(v), Some(s)) = (values, scratch_values) {
                rec.copy(s, 0, v, 0, n)?;
            }
        }
        Ok(())
    }

    /// Invocations of a pass: about [`RADIX_KEYS_PER_INVOCATION`] keys each. A GPU gets whole workgroups of them; a CPU
    /// device runs a partial workgroup rather than give each invocation a few keys, because
    /// every invocation writes, and the scan reads, all [`RADIX_BUCKETS`] of its counters.
    fn threads_for(&self, n: u32) -> u32 {
        let wg = DEFAULT_WORKGROUP_SIZE;
        if self.gpu.info().is_cpu() {
            return n
                .div_ceil(RADIX_KEYS_PER_INVOCATION)
                .clamp(1, self.max_threads.max(1));
        }
        let wanted = n.div_ceil(RADIX_KEYS_PER_INVOCATION).div_ceil(wg) * wg;
        wanted.clamp(wg, self.max_threads.max(wg))
    }

    /// Sorts `keys` on the GPU and reads them back.
    pub fn run_u32(&mut self, keys: &[u32]) -> GpuResult<Vec<u32>> {
        let gpu = self.gpu.clone();
        let buf = GpuBuffer::from_slice(&gpu, "radix sort keys", keys)?;
        gpu.submit(|rec| self.record_u32(rec, &buf, keys.len(), 32))?;
        buf.read()
    }

    /// Sorts `(keys, values)` pairs by key on the GPU and reads them back.
    pub fn run_u64_pairs(
        &mut self,
        keys: &[u64],
        values: &[u32],
        key_bits: u32,
    ) -> GpuResult<(Vec<u64>, Vec<u32>)> {
        let gpu = self.gpu.clone();
        let k = GpuBuffer::from_slice(&gpu, "radix sort keys", keys)?;
        let v = GpuBuffer::from_slice(&gpu, "radix sort values", values)?;
        gpu.submit(|rec| self.record_u64(rec, &k, Some(&v), keys.len(), key_bits))?;
        Ok((k.read()?, v.read()?))
    }
}

/// Records every pass of `job`: count, scan of the histogram, scatter.
fn record_passes(
    rec: &mut Recorder<'_>,
    [count, scatter]: [&Kernel; 2],
    scan: &mut Scan,
    (hist, hist_n): (&GpuBuffer<u32>, &GpuBuffer<u32>),
    job: &Job<'_>,
) -> GpuResult<()> {
    let counted = job.n_at != DeviceAddress::NULL;
    let threads = job.threads;
    let seg_len = job.n.div_ceil(threads).next_multiple_of(4);
    let bits = RADIX_BITS;
    let hist_len = (RADIX_BUCKETS * threads) as usize;
    let groups = count.groups_for(threads as u64);
    for pass in 0..job.key_bits.div_ceil(bits) {
        let (src, dst) = if pass % 2 == 0 {
            job.keys
        } else {
            (job.keys.1, job.keys.0)
        };
        let (vals_in, vals_out) = match job.values {
            Some((a, b)) if pass % 2 == 0 => (a, b),
            Some((a, b)) => (b, a),
            None => (DeviceAddress::NULL, DeviceAddress::NULL),
        };
        let shift = pass * bits;
        let key64 = job.key64 as u32;
        // The last pass may have fewer bits left than a full digit.
        let digit_mask = (1u32 << (job.key_bits - shift).min(bits)) - 1;
        rec.dispatch(
            count,
            groups,
            &[],
            &RadixCountPush {
                keys: src,
                hist: hist.address(),
                n_at: job.n_at,
                hist_n: if counted {
                    hist_n.address()
                } else {
                    DeviceAddress::NULL
                },
                n: job.n,
                seg_len,
                threads,
                shift,
                digit_mask,
                key64,
            },
        )?;
        if counted {
            scan.record_counted(rec, hist, hist, hist_len, hist_n.address(), None)?;
        } else {
            scan.record(rec, hist, hist, hist_len, None)?;
        }
        let push = RadixScatterPush {
            keys_in: src,
            keys_out: dst,
            vals_in,
            vals_out,
            hist: hist.address(),
            n_at: job.n_at,
            n: job.n,
            seg_len,
            threads,
            shift,
            digit_mask,
            key64,
        };
        rec.dispatch(scatter, groups, &[], &push)?;
    }
    Ok(())
}
