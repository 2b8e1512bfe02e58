//! Key validation before a build: duplicates and keys outside the universe, on the GPU (a radix
//! sort of a copy, then a count of equal neighbours) with a plain-Rust twin.

use super::error::HashError;
use super::kernels::HashKernels;
use super::keys::Universe;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer, GpuResult, Recorder};
use crate::kernels::hash;

/// What the check found: the largest key and the duplicates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct KeyCheck {
    /// Largest key (0 when there are none).
    pub max_key: u64,
    /// Occurrences that repeat an earlier key.
    pub duplicates: u64,
    /// The smallest repeated key, if any.
    pub first_duplicate: Option<u64>,
}

impl KeyCheck {
    /// The error this check implies for `universe`, if any.
    pub fn error(&self, n: usize, universe: &Universe) -> Option<HashError> {
        if n > 0 && self.max_key >= universe.key_count() {
            return Some(HashError::KeyOutsideUniverse {
                key: self.max_key,
                universe: universe.key_count(),
                description: universe.describe(),
            });
        }
        self.first_duplicate.map(|key| HashError::DuplicateKey {
            key,
            count: self.duplicates,
        })
    }
}

/// Plain-Rust reference.
pub fn validate_keys_cpu(keys: &[u64]) -> KeyCheck {
    let mut sorted = keys.to_vec();
    sorted.sort_unstable();
    let mut duplicates = 0;
    let mut first_duplicate = None;
    for w in sorted.windows(2) {
        if w[0] == w[1] {
            duplicates += 1;
            first_duplicate = first_duplicate.or(Some(w[0]));
        }
    }
    KeyCheck {
        max_key: sorted.last().copied().unwrap_or(0),
        duplicates,
        first_duplicate,
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct CheckPush<'a> {
        sorted: DeviceAddress<'a>,
        counters: DeviceAddress<'a>,
        key_count: u64,
        n: u32,
        resolution: u32,
    }
}

/// The counters `check_keys.comp` accumulates: duplicates, the smallest duplicate, keys
/// outside, the largest and the smallest of them.
pub(crate) struct CheckCounters(GpuBuffer<u64>);

impl CheckCounters {
    pub(crate) fn new(gpu: &Gpu) -> GpuResult<CheckCounters> {
        Ok(CheckCounters(GpuBuffer::from_slice(
            gpu,
            "key check counters",
            &[0, u64::MAX, 0, 0, u64::MAX],
        )?))
    }

    /// Records the check of `sorted[..n]` against `key_count` and, when `resolution` > 0,
    /// against the `resolution`³ grid of Morton keys.
    pub(crate) fn record(
        &self,
        rec: &mut Recorder<'_>,
        gpu: &Gpu,
        sorted: &GpuBuffer<u64>,
        n: usize,
        key_count: u64,
        resolution: u32,
    ) -> GpuResult<()> {
        let push = CheckPush {
            sorted: sorted.address(),
            counters: self.0.address(),
            key_count,
            n: n as u32,
            resolution,
        };
        let k = gpu.kernel(&hash::CHECK_KEYS)?;
        rec.dispatch(&k, k.groups_for(n as u64), &[], &push)
    }

    /// [duplicates, smallest duplicate, outside, largest outside, smallest outside].
    pub(crate) fn read(&self) -> GpuResult<[u64; 5]> {
        let c = self.0.read()?;
        Ok([c[0], c[1], c[2], c[3], c[4]])
    }
}

/// Checks `keys[..n]` on the GPU: sorts a copy by the universe's key bits, then visits every
/// element for equal neighbours and for keys outside the universe.
pub(crate) fn validate_keys_gpu(
    kernels: &HashKernels,
    keys: &GpuBuffer<u64>,
    n: usize,
    universe: &Universe,
) -> GpuResult<KeyCheck> {
    let gpu = &kernels.gpu;
    if n == 0 {
        return Ok(KeyCheck {
            max_key: 0,
            duplicates: 0,
            first_duplicate: None,
        });
    }
    let copy = GpuBuffer::<u64>::new(gpu, "key check copy", n)?;
    let counters = CheckCounters::new(gpu)?;
    let mut sort = kernels.sort.lock().unwrap();
    gpu.submit(|rec| {
        rec.copy(keys, 0, &copy, 0, n)?;
        sort.record_u64(rec, &copy, None, n, universe.key_bits())?;
        counters.record(rec, gpu, &copy, n, universe.key_count(), 0)
    })?;
    drop(sort);
    let [duplicates, first, outside, max_outside, _] = counters.read()?;
    // Inside the universe the sort was complete, so the largest key is the last one.
    let max_key = if outside > 0 {
        max_outside
    } else {
        copy.read_range(n - 1, 1)?[0]
    };
    Ok(KeyCheck {
        max_key,
        duplicates,
        first_duplicate: (duplicates > 0).then_some(first),
    })
}

/// Checks `keys[..n]` (duplicates, universe) and that no payload exceeds `max_payload`, the
/// limit of the table's cells (`format`, with `bits` payload bits), before a build or insert.
pub(crate) fn validate_entries(
    kernels: &HashKernels,
    universe: &Universe,
    keys: &GpuBuffer<u64>,
    payloads: &GpuBuffer<u32>,
    n: usize,
    (max_payload, format, bits): (u32, String, u32),
) -> Result<(), HashError> {
    if let Some(e) = validate_keys_gpu(kernels, keys, n, universe)?.error(n, universe) {
        return Err(e);
    }
    if n > 0 {
        let result = GpuBuffer::<u32>::new(&kernels.gpu, "payload maximum", 1)?;
        let mut reduce = kernels.reduce.lock().unwrap();
        kernels
            .gpu
            .submit(|rec| reduce.record(rec, payloads, n, crate::prims::ReduceOp::Max, &result))?;
        let max = result.read()?[0];
        if max > max_payload {
            return Err(HashError::PayloadTooLarge {
                payload: max,
                format,
                bits,
                max: max_payload,
            });
        }
    }
    Ok(())
}
