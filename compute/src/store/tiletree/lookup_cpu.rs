//! The CPU reference of `glsl/include/store/tiletree.glsl`, operation for operation: descend
//! to the leaf holding the point, pick the face from the normal, project in parallel onto it,
//! and read the tile (bilinear over 4 texels, or the nearest one).

use super::geometry::{dominant_face, face_axis, plane_axes};
use super::plan::LEAF_WORDS;
use super::refine::LEAF_BIT;
use crate::store::{unpack_rgba8, Filter};
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

/// The lookup at `pos` ([0, 1]³) with surface normal `normal`; (0, 0, 0, 0) in empty space.
/// `Filter::Trilinear` means the tile's bilinear filter (the TileTree's filtered lookup).
pub fn lookup_cpu(host: &TileTreeHost<'_>, pos: Vec3, normal: Vec3, filter: Filter) -> Vec4 {
    let r = host.resolution as f32;
    let g = pos * r;
    let voxel = g.floor().clamp(Vec3::ZERO, Vec3::splat(r - 1.0)).as_uvec3();
    let Some(leaf) = descend(host, voxel.to_array()) else {
        return Vec4::ZERO;
    };
    let rec = &host.leaves[LEAF_WORDS * leaf as usize..][..LEAF_WORDS];
    let origin = [rec[0] & 0xffff, rec[0] >> 16, rec[1] & 0xffff];
    let mask = rec[1] >> 24;
    let face = pick_face(mask, normal);
    let corner = rec[2 + 2 * face as usize];
    let rect = rec[3 + 2 * face as usize];
    let (cx, cy) = (corner & 0xffff, corner >> 16);
    let (x0, y0) = (rect & 0xff, (rect >> 8) & 0xff);
    let (columns, rows) = (((rect >> 16) & 0xff) + 1, (rect >> 24) + 1);
    let (a, _) = face_axis(face);
    let (b, c) = plane_axes(a);
    let tb = (g[b] - (origin[b] + x0) as f32) + 0.5;
    let tc = (g[c] - (origin[c] + y0) as f32) + 0.5;
    let w = host.map_width as usize;
    let texel = |x: u32, y: u32| host.map[(cy + y) as usize * w + (cx + x) as usize];
    match filter {
        Filter::Nearest => {
            let x = ((tb + 0.5).floor().clamp(1.0, columns as f32)) as u32;
            let y = ((tc + 0.5).floor().clamp(1.0, rows as f32)) as u32;
            unpack_rgba8(texel(x, y))
        }
        Filter::Trilinear => {
            let ib = tb.floor().clamp(0.0, columns as f32);
            let ic = tc.floor().clamp(0.0, rows as f32);
            let fx = (tb - ib).clamp(0.0, 1.0);
            let fy = (tc - ic).clamp(0.0, 1.0);
            let (x, y) = (ib as u32, ic as u32);
            let c00 = unpack_rgba8(texel(x, y));
            let c10 = unpack_rgba8(texel(x + 1, y));
            let c01 = unpack_rgba8(texel(x, y + 1));
            let c11 = unpack_rgba8(texel(x + 1, y + 1));
            (c00 * (1.0 - fx) + c10 * fx) * (1.0 - fy) + (c01 * (1.0 - fx) + c11 * fx) * fy
        }
    }
}
