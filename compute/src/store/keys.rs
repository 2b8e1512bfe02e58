//! The check every store applies to the voxel keys it is given: each must be a voxel of the
//! store's R³ grid. It runs on the device (`glsl/hash/check_keys.comp` over the sorted keys),
//! so keys computed by a kernel are never read back to be checked.

use super::error::StoreError;
use super::kernels::StoreKernels;
use crate::hash::{morton_decode, CheckCounters};
use crate::voxel::VoxelKeys;

/// Checks that every key of `keys` lies in the `resolution`³ grid (and is below 2⁶³);
/// the smallest key outside is named.
///
/// # Errors
/// [`StoreError::KeyOutsideGrid`] naming `store`, the key, its voxel and the resolution;
/// device errors.
pub(crate) fn check_keys(
    kernels: &StoreKernels,
    store: &'static str,
    keys: &VoxelKeys,
    resolution: u32,
) -> Result<(), StoreError> {
    if keys.is_empty() {
        return Ok(());
    }
    let gpu = &kernels.gpu;
    let counters = CheckCounters::new(gpu)?;
    gpu.submit(|rec| counters.record(rec, gpu, &keys.keys, keys.len, u64::MAX, resolution))?;
    let [_, _, outside, _, key] = counters.read()?;
    if outside > 0 {
        return Err(StoreError::KeyOutsideGrid {
            store,
            key,
            voxel: morton_decode(key, 3),
            resolution,
        });
    }
    Ok(())
}

/// Plain-Rust twin of `check_keys` for CPU references and tests: the first key outside.
pub fn key_outside_grid(keys: &[u64], resolution: u32) -> Option<u64> {
    keys.iter()
        .copied()
        .find(|&key| key >> 63 != 0 || morton_decode(key, 3).iter().any(|&c| c >= resolution))
}
