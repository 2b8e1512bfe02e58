//! Shelf packing of the tiles into the tile map. Tile sides are T + 2 for a few powers of two
//! T, so sorting by side (largest first) makes each shelf a row of equal tiles: only the end of
//! each shelf and of each size class is lost.

use super::config::{TileTreeConfig, MAX_MAP_TEXELS};
use super::NAME;
use crate::store::StoreError;

/// Where the packer put the tiles.
pub struct Packing {
    /// Tile order: indices into the sides given, largest side first (ties: given order).
    pub order: Vec<usize>,
    /// Lowest corner (x, y) in the map of each tile, in `order`.
    pub corners: Vec<[u32; 2]>,
    /// Map width in texels.
    pub width: u32,
    /// Map height in texels.
    pub height: u32,
}

/// Packs square tiles of `sides` (texels, border included) into one map.
///
/// # Errors
/// A map above [`MAX_MAP_TEXELS`] or taller than the 16-bit tile coordinates of the leaf
/// records allow.
pub fn pack(sides: &[u32], config: &TileTreeConfig) -> Result<Packing, StoreError> {
    let mut order: Vec<usize> = (0..sides.len()).collect();
    order.sort_by(|&x, &y| sides[y].cmp(&sides[x]).then(x.cmp(&y)));
    let area: u64 = sides.iter().map(|&s| s as u64 * s as u64).sum();
    let widest = sides.iter().copied().max().unwrap_or(1);
    // A near-square map whose width is a multiple of the largest side.
    let side = (area as f64).sqrt().ceil() as u64;
    let width = (side.div_ceil(widest as u64) * widest as u64)
        .clamp(widest as u64, config.max_map_width as u64) as u32;
    let mut corners = Vec::with_capacity(sides.len());
    let (mut x, mut y, mut shelf) = (0u32, 0u32, 0u32);
    for &i in &order {
        let s = sides[i];
        if x + s > width {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        corners.push([x, y]);
        x += s;
        shelf = shelf.max(s);
    }
    let height = (y + shelf).max(1);
    let texels = width as u64 * height as u64;
    if texels > MAX_MAP_TEXELS || height as u64 > u16::MAX as u64 {
        return Err(StoreError::Capacity {
            store: NAME,
            what: "tile map texels (width × height, height below 65536)",
            requested: texels.max(height as u64),
            limit: MAX_MAP_TEXELS,
        });
    }
    Ok(Packing {
        order,
        corners,
        width,
        height,
    })
}
