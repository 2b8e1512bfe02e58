//! The CPU reference of the GPU texel fill (`glsl/store/tiletree_*.comp`), step for step:
//!
//! 1. every texel of every tile, border included, is the column through its centre along the
//!    face axis; it takes the voxel of the surface point where that column meets one of the
//!    tile's candidate triangles ([`texel_voxel`]), or is marked empty;
//! 2. its colour is the colour source at that voxel;
//! 3. empty texels take the colour of the nearest filled texel of their row (left first on a
//!    tie), then the still empty ones that of the nearest filled texel of their column (lower
//!    first) — the dilation that keeps bilinear fetches at the edge of the surface from mixing
//!    in undefined colours;
//! 4. the tiles are copied into the tile map.
//!
//! Border texels are computed like interior ones, from the surface just outside the leaf (the
//! candidate triangles reach one texel beyond it in the plane and [`MARGIN`] voxels along the
//! axis): this is the colour duplication that makes bilinear filtering seamless, done by
//! evaluating the neighbouring surface instead of copying the neighbouring tile.

use super::geometry::{column_hit, face_axis, plane_axes, MARGIN};
use super::plan::{Plan, Tile};
use crate::store::HostColours;

/// The voxel a texel takes its colour from and whether it met the surface. Texel (x, y) of a
/// tile with rectangle (x0, y0, w, h) (border included, so its columns are x = 1..=w,
/// y = 1..=h) is the column u = origin_b + x0 + x − 1, v = origin_c + y0 + y − 1 along the face
/// axis a. Among the candidate triangles' hits h
/// within [`MARGIN`] voxels of the leaf's slab [origin_a, origin_a + T], a hit inside the slab
/// wins, nearest the face (largest s·h); else the hit nearest the slab (then largest s·h). The
/// voxel is (floor h, u, v) clamped onto the grid. Without a hit: the voxel at the middle of
/// the slab, marked empty.
pub fn texel_voxel(plan: &Plan, tile: &Tile, x: u32, y: u32) -> ([u32; 3], bool) {
    let r = plan.resolution as i64;
    let (a, s) = face_axis(tile.face);
    let (b, c) = plane_axes(a);
    let u = tile.origin[b] as i64 + tile.rect[0] as i64 + x as i64 - 1;
    let v = tile.origin[c] as i64 + tile.rect[1] as i64 + y as i64 - 1;
    let cu = u as f32 + 0.5;
    let cv = v as f32 + 0.5;
    let lo = tile.origin[a] as f32;
    let hi = (tile.origin[a] + tile.side) as f32;
    let mut best: Option<(u32, f32, f32, f32)> = None;
    let [start, count] = tile.triangles;
    for &t in &plan.tile_triangles[start as usize..(start + count) as usize] {
        let Some(h) = column_hit(plan.surface.vertices(t), a, cu, cv) else {
            continue;
        };
        if h < lo - MARGIN || h > hi + MARGIN {
            continue;
        }
        let (class, dist) = if h >= lo && h <= hi {
            (0, 0.0)
        } else if h < lo {
            (1, lo - h)
        } else {
            (1, h - hi)
        };
        let sh = s * h;
        let better = match best {
            None => true,
            Some((bc, bd, bsh, _)) => {
                class < bc || (class == bc && (dist < bd || (dist == bd && sh > bsh)))
            }
        };
        if better {
            best = Some((class, dist, sh, h));
        }
    }
    let clamp = |w: i64| w.clamp(0, r - 1) as u32;
    let mut voxel = [0u32; 3];
    voxel[b] = clamp(u);
    voxel[c] = clamp(v);
    match best {
        Some((_, _, _, h)) => {
            voxel[a] = clamp(h.floor() as i64);
            (voxel, true)
        }
        None => {
            voxel[a] = clamp(tile.origin[a] as i64 + tile.side as i64 / 2);
            (voxel, false)
        }
    }
}

/// Fills `colours` (texel order) of empty texels from the nearest filled one along rows
/// (`step` 1) or columns (`step` = the tile's stored width); returns the new filled flags.
fn dilate(plan: &Plan, colours: &mut [u32], filled: &[bool], columns: bool) -> Vec<bool> {
    let mut out = filled.to_vec();
    for tile in &plan.tiles {
        let [width, height] = tile.stored_size().map(|s| s as usize);
        let base = tile.texel_offset as usize;
        for y in 0..height {
            for x in 0..width {
                let t = base + y * width + x;
                if filled[t] {
                    continue;
                }
                let (pos, step, len) = if columns {
                    (y, width, height)
                } else {
                    (x, 1, width)
                };
                for d in 1..len {
                    let source = if pos >= d && filled[t - d * step] {
                        Some(t - d * step)
                    } else if pos + d < len && filled[t + d * step] {
                        Some(t + d * step)
                    } else {
                        None
                    };
                    if let Some(src) = source {
                        colours[t] = colours[src];
                        out[t] = true;
                        break;
                    }
                }
            }
        }
    }
    out
}

/// The tile map (row-major RGBA8 words, `map_width × map_height`, 0 outside tiles) that the
/// GPU fill produces for `plan` and `colours` ([`ColourSource::to_host`](crate::store::ColourSource::to_host)). A colour map (a buffer source) colours the texels
/// that meet the surface (0 where it lacks the voxel); the others start at 0.
pub fn fill_cpu(plan: &Plan, colours: &HostColours<'_>) -> Vec<u32> {
    let keyed = matches!(colours, HostColours::Map(_));
    let n = plan.texel_count();
    let mut texel_colours = vec![0u32; n];
    let mut filled = vec![false; n];
    for tile in &plan.tiles {
        let [width, height] = tile.stored_size();
        for y in 0..height {
            for x in 0..width {
                let t = (tile.texel_offset + y * width + x) as usize;
                let (voxel, hit) = texel_voxel(plan, tile, x, y);
                texel_colours[t] = if hit || !keyed {
                    colours.colour(voxel, plan.resolution).unwrap_or(0)
                } else {
                    0
                };
                filled[t] = hit;
            }
        }
    }
    let rows = dilate(plan, &mut texel_colours, &filled, false);
    dilate(plan, &mut texel_colours, &rows, true);
    let width = plan.stats.map_width as usize;
    let mut map = vec![0u32; width * plan.stats.map_height as usize];
    for tile in &plan.tiles {
        let [w, h] = tile.stored_size().map(|s| s as usize);
        for y in 0..h {
            let src = tile.texel_offset as usize + y * w;
            let dst = (tile.corner[1] as usize + y) * width + tile.corner[0] as usize;
            map[dst..dst + w].copy_from_slice(&texel_colours[src..src + w]);
        }
    }
    map
}
