//! Device memory held by buffers, live and at its highest since a mark: what a benchmark needs
//! to state a request's temporary memory as measured rather than estimated. Every buffer and
//! staging allocation goes through [`GpuBuffer`](super::GpuBuffer), which counts it here.

use super::context::Gpu;
use std::sync::atomic::{AtomicU64, Ordering};

/// Counters of allocated bytes (the allocations' sizes, alignment padding included).
#[derive(Debug, Default)]
pub(crate) struct Meter {
    live: AtomicU64,
    peak: AtomicU64,
}

impl Meter {
    pub(crate) fn add(&self, bytes: u64) {
        let now = self.live.fetch_add(bytes, Ordering::Relaxed) + bytes;
        self.peak.fetch_max(now, Ordering::Relaxed);
    }

    pub(crate) fn sub(&self, bytes: u64) {
        self.live.fetch_sub(bytes, Ordering::Relaxed);
    }
}

/// Device memory held by this process's buffers on one [`Gpu`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryUse {
    /// Bytes allocated now.
    pub live: u64,
    /// Most bytes allocated at once since the device was made or [`Gpu::mark_memory`].
    pub peak: u64,
}

impl Gpu {
    /// Device memory held now and at most since the last mark.
    #[must_use]
    pub fn memory_use(&self) -> MemoryUse {
        let m = &self.inner.meter;
        MemoryUse {
            live: m.live.load(Ordering::Relaxed),
            peak: m.peak.load(Ordering::Relaxed),
        }
    }

    /// Starts a new peak from what is held now and returns that: the peak read after some
    /// work, less this, is what the work needed above what it started with.
    pub fn mark_memory(&self) -> u64 {
        let m = &self.inner.meter;
        let live = m.live.load(Ordering::Relaxed);
        m.peak.store(live, Ordering::Relaxed);
        live
    }
}
