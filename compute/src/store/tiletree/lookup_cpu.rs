//! The CPU reference of `glsl/include/store/tiletree.glsl`, operation for operation: descend
//! to the leaf holding the point, pick the face from the normal, project in parallel onto it,
//! and read the tile (bilinear over 4 texels, or the nearest one).

use super::geometry::{dominant_face, face_axis, plane_axes};
use super::plan::LEAF_WORDS;
use super::refine::LEAF_BIT;
use crate::store::{unpack_rgba8, Filter, StoreSample};
use glam::{Vec3, Vec4};

/// What a lookup reads: the tree, the leaf records and the tile map, as on the GPU.
pub struct TileTreeHost<'a> {
    /// R (a power of two).
    pub resolution: u32,
    /// Node cells.
    pub nodes: &'a [u32],
    /// The root's entry.
    pub root: u32,
    /// Leaf records.
    pub leaves: &'a [u32],
    /// Tile map words, row-major.
    pub map: &'a [u32],
    /// Tile map width.
    pub map_width: u32,
}

/// The leaf record index holding voxel `voxel`, or `None` in empty space.
pub fn descend(host: &TileTreeHost<'_>, voxel: [u32; 3]) -> Option<u32> {
    let levels = host.resolution.trailing_zeros();
    let mut e = host.root;
    let mut d = 0;
    while e != 0 && e & LEAF_BIT == 0 && d < levels {
        let shift = levels - 1 - d;
        let oct = ((voxel[0] >> shift) & 1)
            | ((voxel[1] >> shift) & 1) << 1
            | ((voxel[2] >> shift) & 1) << 2;
        e = host.nodes[8 * (e - 1) as usize + oct as usize];
        d += 1;
    }
    (e & LEAF_BIT != 0).then_some(e & !LEAF_BIT)
}

/// The face of a leaf with face mask `mask` that a lookup with normal `n` reads: the dominant
/// one when it has a tile, else the tiled face f with the largest s_f·n_{a_f} (first on ties).
pub fn pick_face(mask: u32, n: Vec3) -> u32 {
    let f = dominant_face(n);
    if mask & (1 << f) != 0 {
        return f;
    }
    let mut best = f32::NEG_INFINITY;
    let mut pick = f;
    for g in 0..6 {
        if mask & (1 << g) != 0 {
            let (a, s) = face_axis(g);
            let score = s * n[a];
            if score > best {
                best = score;
                pick = g;
            }
        }
    }
    pick
}

/// Where a lookup reads in the tile map: the tile of the leaf and face at a point.
struct TileRead<'h, 'a> {
    host: &'h TileTreeHost<'a>,
    /// The tile's map corner.
    corner: (u32, u32),
    /// Its rectangle's columns and rows.
    columns: u32,
    rows: u32,
    /// The in-tile coordinate along the face's two in-plane axes.
    tb: f32,
    tc: f32,
    /// The face's normal axis.
    axis: usize,
}

impl TileRead<'_, '_> {
    fn texel(&self, x: u32, y: u32) -> u32 {
        let w = self.host.map_width as usize;
        self.host.map[(self.corner.1 + y) as usize * w + (self.corner.0 + x) as usize]
    }
}

/// The tile a lookup at `pos` with normal `normal` reads, or `None` in empty space.
fn tile_read<'h, 'a>(
    host: &'h TileTreeHost<'a>,
    pos: Vec3,
    normal: Vec3,
) -> Option<TileRead<'h, 'a>> {
    let r = host.resolution as f32;
    let g = pos * r;
    let voxel = g.floor().clamp(Vec3::ZERO, Vec3::splat(r - 1.0)).as_uvec3();
    let leaf = descend(host, voxel.to_array())?;
    let rec = &host.leaves[LEAF_WORDS * leaf as usize..][..LEAF_WORDS];
    let origin = [rec[0] & 0xffff, rec[0] >> 16, rec[1] & 0xffff];
    let mask = rec[1] >> 24;
    let face = pick_face(mask, normal);
    let corner = rec[2 + 2 * face as usize];
    let rect = rec[3 + 2 * face as usize];
    let (x0, y0) = (rect & 0xff, (rect >> 8) & 0xff);
    let (a, _) = face_axis(face);
    let (b, c) = plane_axes(a);
    Some(TileRead {
        host,
        corner: (corner & 0xffff, corner >> 16),
        columns: ((rect >> 16) & 0xff) + 1,
        rows: (rect >> 24) + 1,
        tb: (g[b] - (origin[b] + x0) as f32) + 0.5,
        tc: (g[c] - (origin[c] + y0) as f32) + 0.5,
        axis: a,
    })
}

/// The bilinear footprint of a tile read: the texel of its (0, 0) corner and the fractions.
fn bilinear_footprint(t: &TileRead<'_, '_>) -> ((u32, u32), f32, f32) {
    let ib = t.tb.floor().clamp(0.0, t.columns as f32);
    let ic = t.tc.floor().clamp(0.0, t.rows as f32);
    let fx = (t.tb - ib).clamp(0.0, 1.0);
    let fy = (t.tc - ic).clamp(0.0, 1.0);
    ((ib as u32, ic as u32), fx, fy)
}

/// The lookup at `pos` ([0, 1]³) with surface normal `normal`; (0, 0, 0, 0) in empty space.
/// `Filter::Trilinear` means the tile's bilinear filter (the TileTree's filtered lookup).
pub fn lookup_cpu(host: &TileTreeHost<'_>, pos: Vec3, normal: Vec3, filter: Filter) -> Vec4 {
    if filter == Filter::Trilinear {
        return sample_cpu(host, pos, normal).sum;
    }
    let Some(t) = tile_read(host, pos, normal) else {
        return Vec4::ZERO;
    };
    let x = ((t.tb + 0.5).floor().clamp(1.0, t.columns as f32)) as u32;
    let y = ((t.tc + 0.5).floor().clamp(1.0, t.rows as f32)) as u32;
    unpack_rgba8(t.texel(x, y))
}

/// The sample lookup (`store_tiletree_sample`): the bilinear sum, coverage 1 on a tile (its
/// texels are all written) and 0 in empty space, and the gradient of alpha in the face's
/// plane (0 along the face's normal axis).
pub fn sample_cpu(host: &TileTreeHost<'_>, pos: Vec3, normal: Vec3) -> StoreSample {
    let Some(t) = tile_read(host, pos, normal) else {
        return StoreSample::default();
    };
    let ((x, y), fx, fy) = bilinear_footprint(&t);
    let c00 = unpack_rgba8(t.texel(x, y));
    let c10 = unpack_rgba8(t.texel(x + 1, y));
    let c01 = unpack_rgba8(t.texel(x, y + 1));
    let c11 = unpack_rgba8(t.texel(x + 1, y + 1));
    let r = host.resolution as f32;
    let mut gradient = Vec3::ZERO;
    let (b, c) = plane_axes(t.axis);
    gradient[b] = ((c10.w - c00.w) * (1.0 - fy) + (c11.w - c01.w) * fy) * r;
    gradient[c] = ((c01.w - c00.w) * (1.0 - fx) + (c11.w - c10.w) * fx) * r;
    StoreSample {
        sum: (c00 * (1.0 - fx) + c10 * fx) * (1.0 - fy) + (c01 * (1.0 - fx) + c11 * fx) * fy,
        coverage: 1.0,
        gradient,
    }
}
