//! Errors of the sparse stores: each names the store, the key or the limit at fault.

use crate::gpu::GpuError;
use crate::hash::HashError;

/// Why a store could not be built, extended or queried.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// A voxel key lies outside the store's R³ grid.
    #[error("{store} store: voxel key {key} (voxel {voxel:?}) is outside the {resolution}³ grid")]
    KeyOutsideGrid {
        /// The store.
        store: &'static str,
        /// The Morton key.
        key: u64,
        /// Its voxel.
        voxel: [u32; 3],
        /// The grid's resolution.
        resolution: u32,
    },
    /// An inserted voxel is stored already.
    #[error("{store} store: voxel {voxel:?} is stored already ({count} inserted voxel(s) were); insert adds new voxels only")]
    AlreadyStored {
        /// The store.
        store: &'static str,
        /// One such voxel (`[0, 0, 0]` when only the count is known).
        voxel: [u32; 3],
        /// How many were.
        count: u64,
    },
    /// A device colour source lacks a voxel the store needs.
    #[error("{store} store: the colour source has no colour for voxel {voxel:?} ({count} voxel(s) the store needs are missing from its keys)")]
    MissingColour {
        /// The store.
        store: &'static str,
        /// The smallest missing voxel's position.
        voxel: [u32; 3],
        /// How many are missing.
        count: u64,
    },
    /// A colour uses an alpha value the store reserves for its own tags.
    #[error("{store} store: voxel {voxel:?} has colour {rgba:#010x} whose alpha {alpha} is below {min_alpha}, which the store reserves for its tags")]
    ReservedAlpha {
        /// The store.
        store: &'static str,
        /// The voxel.
        voxel: [u32; 3],
        /// The colour.
        rgba: u32,
        /// Its alpha.
        alpha: u32,
        /// The smallest allowed alpha.
        min_alpha: u32,
    },
    /// A configuration value out of range.
    #[error("{store} store: {problem}")]
    Config {
        /// The store.
        store: &'static str,
        /// What is wrong, with the limit.
        problem: String,
    },
    /// The store outgrew an addressing limit.
    #[error("{store} store: {what} needs {requested}, above the limit of {limit}")]
    Capacity {
        /// The store.
        store: &'static str,
        /// What outgrew the limit.
        what: &'static str,
        /// What was needed.
        requested: u64,
        /// The limit.
        limit: u64,
    },
    /// The store does not offer this operation.
    #[error("{store} store: {what} is not supported")]
    Unsupported {
        /// The store.
        store: &'static str,
        /// The operation, and what to do instead.
        what: &'static str,
    },
    /// The hash table failed.
    #[error(transparent)]
    Hash(#[from] HashError),
    /// The device failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
}
