//! Errors of the hash tables: each says which limit or key is at fault.

use crate::gpu::GpuError;

/// Why a table could not be built or extended.
#[derive(Debug, thiserror::Error)]
pub enum HashError {
    /// A key occurs more than once.
    #[error(
        "duplicate key {key} ({count} repeated occurrence(s)); hash tables hold each key once"
    )]
    DuplicateKey {
        /// The smallest repeated key.
        key: u64,
        /// How many occurrences repeat an earlier one.
        count: u64,
    },
    /// A key lies outside the universe.
    #[error("key {key} is outside the universe of {universe} keys ({description})")]
    KeyOutsideUniverse {
        /// The largest offending key.
        key: u64,
        /// Number of keys in the universe.
        universe: u64,
        /// The universe, e.g. `2D 4096x4096 Morton`.
        description: String,
    },
    /// A payload does not fit the cell.
    #[error("payload {payload} does not fit: {format} leaves {bits} payload bits (largest payload {max})")]
    PayloadTooLarge {
        /// The largest payload given.
        payload: u32,
        /// The cell format.
        format: String,
        /// Payload bits available.
        bits: u32,
        /// Largest storable payload.
        max: u32,
    },
    /// The universe's keys do not fit the cell width.
    #[error("{universe} needs {key_bits} key bits, which leaves no payload bits in a {cell_bits}-bit cell")]
    UniverseTooLarge {
        /// The universe.
        universe: String,
        /// Bits of key + 1.
        key_bits: u32,
        /// Cell width.
        cell_bits: u32,
    },
    /// More keys than the configured maximum load factor allows.
    #[error("table full: {keys} keys in {capacity} cells is a load factor of {load:.4}, above the configured maximum {max_load_factor}")]
    TableFull {
        /// Keys the table would hold.
        keys: u64,
        /// Cells.
        capacity: u64,
        /// The resulting load factor.
        load: f64,
        /// The configured maximum.
        max_load_factor: f64,
    },
    /// Robin Hood insertion pushed keys past the largest age the 4-bit field can hold.
    #[error("{failed} key(s) would need a probe age above {max_age} (the 4-bit age field) at load factor {load_factor:.4} in {table_size} cells; build at a lower load factor or allow growth")]
    AgeOverflow {
        /// Keys left unplaced.
        failed: u32,
        /// The largest storable age.
        max_age: u32,
        /// The load factor tried.
        load_factor: f64,
        /// Cells.
        table_size: u32,
    },
    /// Cuckoo construction failed with every set of hash constants tried.
    #[error("cuckoo construction failed {attempts} times at load factor {load_factor:.4} ({failed} key(s) unplaced in the last attempt); lower the load factor")]
    CuckooFailed {
        /// Attempts made.
        attempts: u32,
        /// The load factor.
        load_factor: f64,
        /// Keys unplaced in the last attempt.
        failed: u32,
    },
    /// Perfect-hash construction found no offset for some bucket at every |Φ| tried.
    #[error("perfect hash construction failed after {attempts} attempt(s); the last, {sizes}, failed because {reason}")]
    PerfectHashFailed {
        /// Attempts made.
        attempts: u32,
        /// Sizes of the last attempt.
        sizes: String,
        /// Why the last attempt failed.
        reason: String,
    },
    /// A parameter out of range.
    #[error("{0}")]
    InvalidArgument(String),
    /// A GPU failure.
    #[error(transparent)]
    Gpu(#[from] GpuError),
}
