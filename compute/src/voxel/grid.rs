//! The two grids a surface is voxelized on: the voxels themselves, and the interpolation cells
//! of trilinear filtering (the cubes between eight neighbouring voxel centres), which form the
//! same grid shifted by half a voxel.

use super::error::VoxelError;

/// Largest voxel resolution: Morton keys of the shifted 2049³ grid still fit 36 bits, and
/// every count stays within the primitives' signed 32-bit limit for the meshes lazysolid uses.
pub const MAX_RESOLUTION: u32 = 2048;

/// A regular grid over the unit cube with cells of size 1/R.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VoxelGrid {
    /// R: voxels per axis (any value in 1..=[`MAX_RESOLUTION`], power of two or not).
    pub resolution: u32,
    /// False: voxel i covers [i/R, (i+1)/R]. True: the interpolation-cell grid, where cell j
    /// covers [(j−0.5)/R, (j+0.5)/R], j in 0..=R (cell j has voxel centres j−1 and j as
    /// corners along each axis).
    pub shifted: bool,
}

impl VoxelGrid {
    /// The voxel grid of resolution `resolution`.
    pub fn voxels(resolution: u32) -> Result<VoxelGrid, VoxelError> {
        Self::new(resolution, false)
    }

    /// The interpolation-cell grid of voxels of resolution `resolution`.
    pub fn cells(resolution: u32) -> Result<VoxelGrid, VoxelError> {
        Self::new(resolution, true)
    }

    fn new(resolution: u32, shifted: bool) -> Result<VoxelGrid, VoxelError> {
        if resolution == 0 || resolution > MAX_RESOLUTION {
            return Err(VoxelError::Resolution {
                resolution,
                max: MAX_RESOLUTION,
            });
        }
        Ok(VoxelGrid {
            resolution,
            shifted,
        })
    }

    /// Cells per axis: R, or R + 1 for the shifted grid.
    pub fn extent(&self) -> u32 {
        self.resolution + self.shifted as u32
    }

    /// Bits per axis of the power-of-two cube the Morton keys live in.
    pub fn axis_bits(&self) -> u32 {
        self.extent().next_power_of_two().trailing_zeros()
    }

    /// Significant bits of a Morton key (at least 1, the radix sort's minimum).
    pub fn key_bits(&self) -> u32 {
        (3 * self.axis_bits()).max(1)
    }

    /// Cell i's centre is (i + offset) / R.
    pub fn center_offset(&self) -> f32 {
        if self.shifted {
            0.0
        } else {
            0.5
        }
    }

    /// Added to v·R to get the grid coordinate (in which cell i spans [i, i + 1]).
    pub fn grid_shift(&self) -> f32 {
        if self.shifted {
            0.5
        } else {
            0.0
        }
    }
}
