//! Shelf packing of the rectangular tiles into the tile map: sorted by height (tallest first,
//! then widest), each shelf holds tiles of nearly one height, so little is lost above the
//! shorter ones and at the end of each shelf.

use super::config::{TileTreeConfig, MAX_MAP_TEXELS};
use super::NAME;
use crate::store::StoreError;

/// Where the packer put the tiles.
pub struct Packing {
    /// Tile order: indices into the sizes given, tallest first, then widest (ties: given order).
    pub order: Vec<usize>,
    /// Lowest corner (x, y) in the map of each tile, in `order`.
    pub corners: Vec<[u32; 2]>,
    /// Map width in texels.
    pub width: u32,
    /// Map height in texels.
    pub height: u32,
}

/// Packs tiles of `sizes` (width, height in texels, border included) into one map.
///
/// # Errors
/// A map above [`MAX_MAP_TEXELS`] or taller than the 16-bit tile coordinates of the leaf
/// records allow.
pub fn pack(sizes: &[[u32; 2]], config: &TileTreeConfig) -> Result<Packing, StoreError> {
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by(|&x, &y| {
        let (a, b) = (sizes[x], sizes[y]);
        b[1].cmp(&a[1]).then(b[0].cmp(&a[0])).then(x.cmp(&y))
    });
    let area: u64 = sizes.iter().map(|s| s[0] as u64 * s[1] as u64).sum();
    let widest = sizes.iter().map(|s| s[0]).max().unwrap_or(1);
    // A near-square map, at least as wide as the widest tile.
    let side = (area as f64).sqrt().ceil() as u64;
    let width = side.clamp(widest as u64, config.max_map_width as u64) as u32;
    let mut corners = Vec::with_capacity(sizes.len());
    let (mut x, mut y, mut shelf) = (0u32, 0u32, 0u32);
    for &i in &order {
        let [w, h] = sizes[i];
        if x + w > width {
            y += shelf;
            x = 0;
            shelf = 0;
        }
        corners.push([x, y]);
        x += w;
        shelf = shelf.max(h);
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
