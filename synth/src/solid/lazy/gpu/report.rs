//! What each request of a lazy state did: the figures `bench lazy`, `bench cuts` and the
//! renderer print.

/// What one request did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LazyReport {
    /// Voxels in each level's dependency set, coarsest first.
    pub needed: Vec<u64>,
    /// Voxel versions computed at each level (upsampled or corrected), coarsest first.
    pub computed: Vec<u64>,
    /// Voxels new to the state at each level (each upsampled once; the rest of `computed`
    /// are corrections), coarsest first.
    pub upsampled: Vec<u64>,
    /// Device time of the synthesis kernels, milliseconds.
    pub gpu_ms: f64,
    /// Wall time of the dependency walk, milliseconds.
    pub deps_ms: f64,
    /// Wall time of the whole request, milliseconds.
    pub wall_ms: f64,
    /// Chunks the request ran in (`policy.rs`).
    pub chunks: u32,
    /// The largest state alive during the request, before the policy applied (bytes).
    pub peak_state_bytes: u64,
    /// Levels the policy emptied or cut back after the request's last chunk.
    pub dropped_levels: u32,
    /// Dependency walks run: one per chunk, and one more for each walk whose sets outgrew
    /// the walk's buffers (`walk.rs`).
    pub walks: u32,
    /// Submissions the host waited for during the request (the policy's included).
    pub waits: u64,
    /// Level hash tables made, rebuilt larger or refilled after an age overflowed: the
    /// waits a request adds to its fixed few per chunk, besides retried walks.
    pub table_growths: u32,
}

impl LazyReport {
    /// Adds one chunk's report to this one.
    pub(super) fn add(&mut self, chunk: &LazyReport) {
        let sum = |a: &mut Vec<u64>, b: &[u64]| {
            a.resize(a.len().max(b.len()), 0);
            for (x, y) in a.iter_mut().zip(b) {
                *x += y;
            }
        };
        sum(&mut self.needed, &chunk.needed);
        sum(&mut self.computed, &chunk.computed);
        sum(&mut self.upsampled, &chunk.upsampled);
        self.gpu_ms += chunk.gpu_ms;
        self.deps_ms += chunk.deps_ms;
        self.chunks += 1;
        self.walks += chunk.walks;
        self.waits += chunk.waits;
        self.table_growths += chunk.table_growths;
        self.peak_state_bytes = self.peak_state_bytes.max(chunk.peak_state_bytes);
    }
}
