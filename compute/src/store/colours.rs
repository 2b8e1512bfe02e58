//! Where texel colours come from: the procedural marble evaluated on the GPU, or any function of
//! the voxel evaluated on the CPU.

use super::error::StoreError;
use crate::gpu::{DeviceAddress, Gpu, GpuBuffer};
use crate::hash::morton_decode;
use crate::kernels::store;
use crate::voxel::VoxelKeys;

/// The colour (RGBA8, red in the low byte) of each voxel a store is built from or extended by.
#[derive(Clone, Copy)]
pub enum ColourSource<'a> {
    /// [`marble_rgba8`](super::marble_rgba8) with this seed, filled on the GPU.
    Marble {
        /// Noise seed.
        seed: u32,
    },
    /// The colour of voxel `[x, y, z]`, evaluated on the CPU (the keys are read back).
    Fn(&'a (dyn Fn([u32; 3]) -> u32 + Sync)),
}

impl ColourSource<'_> {
    /// The colour of one voxel, for CPU references.
    pub fn colour(&self, voxel: [u32; 3], resolution: u32) -> u32 {
        match self {
            ColourSource::Marble { seed } => super::marble_rgba8(voxel, resolution, *seed),
            ColourSource::Fn(f) => f(voxel),
        }
    }
}

crate::push_block! {
    #[derive(Clone, Copy)]
    pub(crate) struct FillPush<'a> {
        keys: DeviceAddress<'a>,
        dst: DeviceAddress<'a>,
        n: u32,
        resolution: u32,
        seed: u32,
    }
}

/// Writes the colours of `keys` into `dst[offset..offset + keys.len]`.
pub(crate) fn fill_colours(
    gpu: &Gpu,
    keys: &VoxelKeys,
    source: &ColourSource<'_>,
    resolution: u32,
    dst: &mut GpuBuffer<u32>,
    offset: usize,
) -> Result<(), StoreError> {
    match source {
        ColourSource::Marble { seed } => {
            let fill = gpu.kernel(&store::FILL_MARBLE)?;
            gpu.submit(|rec| {
                let push = FillPush {
                    keys: keys.keys.address(),
                    dst: dst.address_at(offset)?,
                    n: keys.len as u32,
                    resolution,
                    seed: *seed,
                };
                rec.dispatch(&fill, fill.groups_for(keys.len as u64), &[], &push)
            })?;
        }
        ColourSource::Fn(f) => {
            let colours: Vec<u32> = keys
                .read()?
                .into_iter()
                .map(|k| f(morton_decode(k, 3)))
                .collect();
            dst.write(offset, &colours)?;
        }
    }
    Ok(())
}

/// Checks that every key lies in the `resolution`³ grid.
pub(crate) fn check_keys(
    store: &'static str,
    keys: &[u64],
    resolution: u32,
) -> Result<(), StoreError> {
    for &key in keys {
        let voxel = morton_decode(key, 3);
        if voxel.iter().any(|&c| c >= resolution) || key >> 63 != 0 {
            return Err(StoreError::KeyOutsideGrid {
                store,
                key,
                voxel,
                resolution,
            });
        }
    }
    Ok(())
}
