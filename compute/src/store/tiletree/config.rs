//! The knobs of a TileTree and the limits they are checked against.

use super::NAME;
use crate::store::StoreError;
use crate::voxel::MAX_RESOLUTION;

/// Largest tile map side in texels (the per-leaf records keep 16-bit tile coordinates).
pub const MAX_MAP_SIDE: u32 = 1 << 15;
/// Largest tile side T (`max_tile`): a leaf record keeps a tile's rectangle in 8-bit fields.
pub const MAX_TILE: u32 = 256;
/// Largest tile map in texels (RGBA8 words): 512 MiB, well inside one device allocation.
pub const MAX_MAP_TEXELS: u64 = 1 << 27;

/// How finely the octree is refined and tiled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileTreeConfig {
    /// Largest tile side T (texels without border, at most [`MAX_TILE`]): nodes with larger
    /// tiles are always split. Tiles are cropped to the surface they carry, so larger leaves
    /// cost fewer borders and records without paying for empty face area (32 gave the smallest
    /// armadillo at 1024, see `docs/stores.md`).
    pub max_tile: u32,
    /// Smallest tile side T: the maximum depth. A leaf at this size keeps a fold if it has one
    /// (counted in [`TileTreeStats::folded_leaves`](super::TileTreeStats)).
    pub min_tile: u32,
    /// Widest tile map allowed (texels); the packer picks a near-square width below it.
    pub max_map_width: u32,
}

impl Default for TileTreeConfig {
    fn default() -> Self {
        TileTreeConfig {
            max_tile: 32,
            min_tile: 4,
            max_map_width: 16384,
        }
    }
}

impl TileTreeConfig {
    /// Checks the configuration against the equivalent resolution R.
    pub fn check(&self, resolution: u32) -> Result<(), StoreError> {
        let problem = if !resolution.is_power_of_two()
            || !(2..=MAX_RESOLUTION).contains(&resolution)
        {
            Some(format!(
                "equivalent resolution R = {resolution} must be a power of two in 2..={MAX_RESOLUTION} (tile sides are R / 2^depth)"
            ))
        } else if !self.max_tile.is_power_of_two() || !self.min_tile.is_power_of_two() {
            Some(format!(
                "max_tile = {} and min_tile = {} must be powers of two",
                self.max_tile, self.min_tile
            ))
        } else if self.max_tile > MAX_TILE {
            Some(format!(
                "max_tile = {} exceeds {MAX_TILE} (tile rectangles are 8-bit fields of the leaf records)",
                self.max_tile
            ))
        } else if self.min_tile > self.max_tile {
            Some(format!(
                "min_tile = {} exceeds max_tile = {}",
                self.min_tile, self.max_tile
            ))
        } else if self.min_tile > resolution {
            Some(format!(
                "min_tile = {} exceeds the resolution R = {resolution}",
                self.min_tile
            ))
        } else if self.max_map_width < self.max_tile.min(resolution) + 2
            || self.max_map_width > MAX_MAP_SIDE
        {
            Some(format!(
                "max_map_width = {} must lie in {}..={MAX_MAP_SIDE} (the largest tile with its border)",
                self.max_map_width,
                self.max_tile.min(resolution) + 2
            ))
        } else {
            None
        };
        match problem {
            Some(problem) => Err(StoreError::Config {
                store: NAME,
                problem,
            }),
            None => Ok(()),
        }
    }
}
