//! Everything of a TileTree that the CPU decides: the refined octree, the tiles and their place
//! in the tile map, the leaf records the lookup reads, and per tile the triangles its texels may
//! hit. The GPU fill (and its CPU reference) turn a plan and a colour source into the tile map.

use super::config::TileTreeConfig;
use super::geometry::Surface;
use super::pack::pack;
use super::refine::{refine, Leaf};
use crate::store::StoreError;
use glam::Vec3;

/// Words of a leaf record: origin x | y << 16; origin z | depth << 16 | face mask << 24; then
/// for each of the six faces two words (0 when absent): its tile's map corner x | y << 16, and
/// its rectangle of columns x0 | y0 << 8 | (w − 1) << 16 | (h − 1) << 24 ([`Tile::rect`]; the
/// tile sides are at most [`MAX_TILE`](super::config::MAX_TILE) = 256).
pub const LEAF_WORDS: usize = crate::shader_constants::TILETREE_LEAF_WORDS as usize;
/// Words of a tile record on the GPU (see [`Tile::record`]).
pub const TILE_WORDS: usize = crate::shader_constants::TILETREE_TILE_WORDS as usize;

/// One tile: the texels of a rectangle of columns of one face of one leaf, w × h plus a
/// one-texel border.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tile {
    /// Its leaf.
    pub leaf: u32,
    /// Its face (2·axis + (sign < 0)).
    pub face: u32,
    /// The leaf's lowest corner, voxels.
    pub origin: [u32; 3],
    /// T: the leaf's side in voxels (its slab along the face axis).
    pub side: u32,
    /// The columns it covers, border excluded: first column along the face's in-plane axes
    /// (b, c) relative to the leaf's origin, width w and height h.
    pub rect: [u32; 4],
    /// Lowest corner in the tile map.
    pub corner: [u32; 2],
    /// Index of its first texel in texel order (tiles in packing order, rows of w + 2).
    pub texel_offset: u32,
    /// Its candidate triangles: `Plan::tile_triangles[start..start + count]`.
    pub triangles: [u32; 2],
}

impl Tile {
    /// Texels per row and per column with the border: w + 2, h + 2.
    pub fn stored_size(&self) -> [u32; 2] {
        [self.rect[2] + 2, self.rect[3] + 2]
    }

    /// The GPU record: origin xyz, T, face, triangle start, count, texel offset, corner xy,
    /// x0 | y0 << 16, w | h << 16.
    pub fn record(&self) -> [u32; TILE_WORDS] {
        [
            self.origin[0],
            self.origin[1],
            self.origin[2],
            self.side,
            self.face,
            self.triangles[0],
            self.triangles[1],
            self.texel_offset,
            self.corner[0],
            self.corner[1],
            self.rect[0] | self.rect[1] << 16,
            self.rect[2] | self.rect[3] << 16,
        ]
    }
}

/// Counts that describe a built tree.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TileTreeStats {
    /// Interior nodes.
    pub nodes: usize,
    /// Leaves.
    pub leaves: usize,
    /// Leaves at the maximum depth that still hold a fold.
    pub folded_leaves: usize,
    /// Leaves per depth (index = depth).
    pub leaves_per_depth: Vec<usize>,
    /// Tiles (faces with texels) per leaf count: `tiles_per_leaf[k]` leaves have k + 1 tiles.
    pub tiles_per_leaf: [usize; 6],
    /// Tiles.
    pub tiles: usize,
    /// Texels of all tiles, borders included.
    pub tile_texels: u64,
    /// Tile map size.
    pub map_width: u32,
    /// Tile map size.
    pub map_height: u32,
}

impl TileTreeStats {
    /// Fraction of the tile map covered by tiles.
    pub fn occupancy(&self) -> f64 {
        self.tile_texels as f64 / (self.map_width as f64 * self.map_height as f64)
    }
}

/// The CPU-side decisions of a TileTree.
pub struct Plan {
    /// R.
    pub resolution: u32,
    /// The mesh in grid units.
    pub surface: Surface,
    /// Node cells (8 per node; entries: 0 empty, node index + 1, or `LEAF_BIT | leaf`).
    pub nodes: Vec<u32>,
    /// The root's entry.
    pub root: u32,
    /// The leaves.
    pub leaves: Vec<Leaf>,
    /// Leaf records, [`LEAF_WORDS`] per leaf.
    pub leaf_records: Vec<u32>,
    /// Tiles in packing (and texel) order.
    pub tiles: Vec<Tile>,
    /// Candidate triangles of all tiles.
    pub tile_triangles: Vec<u32>,
    /// Counts.
    pub stats: TileTreeStats,
}

impl Plan {
    /// Refines, tiles and packs the mesh (unit-cube coordinates) at equivalent resolution
    /// `resolution`.
    ///
    /// # Errors
    /// A bad configuration or resolution, an empty or malformed mesh, or a tile map above the
    /// limits.
    pub fn new(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
        config: TileTreeConfig,
    ) -> Result<Plan, StoreError> {
        config.check(resolution)?;
        let surface = Surface::new(positions, triangles, resolution)?;
        let refined = refine(&surface, resolution, config);
        let sizes: Vec<[u32; 2]> = refined
            .faces
            .iter()
            .map(|f| [f.rect[2] + 2, f.rect[3] + 2])
            .collect();
        let packing = pack(&sizes, &config)?;
        let mut tiles = Vec::with_capacity(sizes.len());
        let mut tile_triangles = Vec::new();
        let mut texels = 0u64;
        let mut leaf_records = vec![0u32; LEAF_WORDS * refined.leaves.len()];
        for (leaf, l) in refined.leaves.iter().enumerate() {
            let w = &mut leaf_records[LEAF_WORDS * leaf..];
            w[0] = l.origin[0] | l.origin[1] << 16;
            w[1] = l.origin[2] | l.depth << 16 | l.mask << 24;
        }
        for (&i, &corner) in packing.order.iter().zip(&packing.corners) {
            let f = &refined.faces[i];
            let l = &refined.leaves[f.leaf as usize];
            let tile = Tile {
                leaf: f.leaf,
                face: f.face,
                origin: l.origin,
                side: resolution >> l.depth,
                rect: f.rect,
                corner,
                texel_offset: texels as u32,
                triangles: [tile_triangles.len() as u32, f.triangles.len() as u32],
            };
            tile_triangles.extend_from_slice(&f.triangles);
            texels += sizes[i][0] as u64 * sizes[i][1] as u64;
            let w = &mut leaf_records[LEAF_WORDS * f.leaf as usize + 2 + 2 * f.face as usize..];
            w[0] = corner[0] | corner[1] << 16;
            let [x0, y0, width, height] = f.rect;
            w[1] = x0 | y0 << 8 | (width - 1) << 16 | (height - 1) << 24;
            tiles.push(tile);
        }
        let mut stats = TileTreeStats {
            nodes: refined.nodes.len() / 8,
            leaves: refined.leaves.len(),
            folded_leaves: refined.leaves.iter().filter(|l| l.folded).count(),
            tiles: tiles.len(),
            tile_texels: texels,
            map_width: packing.width,
            map_height: packing.height,
            ..Default::default()
        };
        for l in &refined.leaves {
            let d = l.depth as usize;
            if stats.leaves_per_depth.len() <= d {
                stats.leaves_per_depth.resize(d + 1, 0);
            }
            stats.leaves_per_depth[d] += 1;
            stats.tiles_per_leaf[l.mask.count_ones() as usize - 1] += 1;
        }
        Ok(Plan {
            resolution,
            surface,
            nodes: refined.nodes,
            root: refined.root,
            leaves: refined.leaves,
            leaf_records,
            tiles,
            tile_triangles,
            stats,
        })
    }

    /// Texels of all tiles (texel order), borders included.
    pub fn texel_count(&self) -> usize {
        self.stats.tile_texels as usize
    }

    /// The tile records for the GPU, [`TILE_WORDS`] each, followed by nothing else.
    pub fn tile_records(&self) -> Vec<u32> {
        self.tiles.iter().flat_map(|t| t.record()).collect()
    }
}
