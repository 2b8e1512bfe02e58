//! Host waits and device time of submissions, counted: what a benchmark needs to split a
//! request's wall time into device work and everything else (host code, allocation, the
//! round trips themselves), and what a test needs to bound the round trips a request makes.
//! Every submission goes through [`Gpu::submit_timed`](super::Gpu::submit_timed) and waits
//! for its fence once, so one submission is one host wait.

use super::context::Gpu;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;

/// Most dispatches of one submission timed one by one while profiling; later ones count as
/// untimed (`KernelTime::untimed`).
pub(crate) const PROFILED_DISPATCHES: u32 = 2048;

/// Counters of submissions and, while timing is on, their device time.
#[derive(Debug, Default)]
pub(crate) struct SubmissionMeter {
    waits: AtomicU64,
    timed: AtomicU64,
    device_ns: AtomicU64,
    timing: AtomicBool,
    profiling: AtomicBool,
    kernels: Mutex<BTreeMap<&'static str, KernelTime>>,
}

impl SubmissionMeter {
    /// Counts one submission waited for.
    pub(crate) fn waited(&self) {
        self.waits.fetch_add(1, Ordering::Relaxed);
    }

    /// Whether submissions bracket their commands with timestamps.
    pub(crate) fn timing(&self) -> bool {
        self.timing.load(Ordering::Relaxed)
    }

    /// Whether every dispatch is bracketed by timestamps of its own.
    pub(crate) fn profiling(&self) -> bool {
        self.profiling.load(Ordering::Relaxed)
    }

    /// Adds the device time of one dispatch of `kernel` (`None`: past the submission's
    /// [`PROFILED_DISPATCHES`], untimed).
    pub(crate) fn add_dispatch(&self, kernel: &'static str, ns: Option<f64>) {
        let mut kernels = self.kernels.lock().unwrap();
        let k = kernels.entry(kernel).or_insert_with(|| KernelTime {
            kernel,
            ..KernelTime::default()
        });
        k.dispatches += 1;
        match ns {
            Some(ns) => k.device_ns += ns,
            None => k.untimed += 1,
        }
    }

    /// Adds the device time of one bracketed submission.
    pub(crate) fn add_device_ns(&self, ns: f64) {
        self.timed.fetch_add(1, Ordering::Relaxed);
        self.device_ns
            .fetch_add(ns.round() as u64, Ordering::Relaxed);
    }
}

/// Submissions made on one [`Gpu`] so far; differences of two readings describe the work
/// between them ([`Submissions::since`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Submissions {
    /// Submissions the host waited for (one fence wait each), staging copies included.
    pub waits: u64,
    /// Submissions whose device time is in `device_ns` (those made while timing was on).
    pub timed: u64,
    /// Device time of the timed submissions: from a timestamp before their first command to
    /// one after their last, summed, in nanoseconds.
    pub device_ns: u64,
}

impl Submissions {
    /// What happened between `before` and this reading.
    #[must_use]
    pub fn since(self, before: Submissions) -> Submissions {
        Submissions {
            waits: self.waits - before.waits,
            timed: self.timed - before.timed,
            device_ns: self.device_ns - before.device_ns,
        }
    }

    /// Device time in milliseconds.
    pub fn device_ms(&self) -> f64 {
        self.device_ns as f64 * 1e-6
    }
}

/// Device time of one kernel's dispatches while profiling
/// ([`Gpu::profile_dispatches`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct KernelTime {
    /// The kernel's name (its GLSL file's stem).
    pub kernel: &'static str,
    /// Dispatches recorded.
    pub dispatches: u64,
    /// Dispatches past a submission's limit of timed ones, not in `device_ns`.
    pub untimed: u64,
    /// Device time from a timestamp before each dispatch to one after it, summed.
    pub device_ns: f64,
}

impl Gpu {
    /// Submissions so far on this device.
    #[must_use]
    pub fn submissions(&self) -> Submissions {
        let m = &self.inner.submissions;
        Submissions {
            waits: m.waits.load(Ordering::Relaxed),
            timed: m.timed.load(Ordering::Relaxed),
            device_ns: m.device_ns.load(Ordering::Relaxed),
        }
    }

    /// Whether every submission from now on is bracketed by two timestamps whose difference
    /// adds to [`Submissions::device_ns`]. Off by default: the bracket costs a query pool per
    /// submission, which benchmarks pay to know their device time and nothing else should.
    pub fn time_submissions(&self, on: bool) {
        self.inner.submissions.timing.store(on, Ordering::Relaxed);
    }

    /// Whether every dispatch from now on is bracketed by two timestamps of its own, summed
    /// per kernel for [`Gpu::take_dispatch_profile`]. Off by default: the timestamps
    /// serialize the dispatches' ends, which a profile accepts and a timing should not.
    pub fn profile_dispatches(&self, on: bool) {
        self.inner
            .submissions
            .profiling
            .store(on, Ordering::Relaxed);
    }

    /// The dispatch profile gathered since the last call, most device time first.
    pub fn take_dispatch_profile(&self) -> Vec<KernelTime> {
        let kernels = std::mem::take(&mut *self.inner.submissions.kernels.lock().unwrap());
        let mut v: Vec<KernelTime> = kernels.into_values().collect();
        v.sort_by(|a, b| b.device_ns.total_cmp(&a.device_ns));
        v
    }
}
