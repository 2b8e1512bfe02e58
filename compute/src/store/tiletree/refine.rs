//! The octree around the surface, refined on the CPU: a node is split while its tiles are
//! larger than `max_tile`, or while one of its faces shows a fold (two surface sheets over one
//! texel column, more than [`FOLD_TOLERANCE`] voxels apart), down to `min_tile`.
//!
//! A leaf's candidate faces are the dominant normal directions of its triangles. A face is
//! dropped when every triangle a lookup would read through it lies in the cone of another kept
//! face (whose fill sees that triangle, and whose fold test passed over it), fewest triangles
//! first; each kept face's tile is then cropped to the rectangle of columns its triangles cover
//! (counting those within [`SWITCH_MARGIN`] of picking it). Together they halve the tile map.
//!
//! The fold test rasterizes, per present face, the triangles of the face's cone that overlap
//! the leaf at the T × T texel-column centres of the face with [`column_hit`] (the function
//! the texel fill uses), keeping per column the lowest and highest hit inside the leaf's slab.
//! It sees exactly the columns the tiles store, so a leaf that passes projects injectively at
//! every stored texel; surface between column centres (slivers thinner than a texel) is not
//! seen, and sheets closer than [`FOLD_TOLERANCE`] count as one.

use super::config::TileTreeConfig;
use super::geometry::{
    column_hit, face_axis, plane_axes, Surface, FOLD_TOLERANCE, MARGIN, SWITCH_MARGIN,
};
use super::lookup_cpu::pick_face;
use crate::voxel::triangle_box_overlap;
use glam::Vec3;

/// Entry bit marking a leaf index in a node cell (else the cell holds child node index + 1,
/// or 0 for empty space).
pub const LEAF_BIT: u32 = 1 << 31;

/// One leaf: a cube of side T = R >> depth at `origin` (voxels).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Leaf {
    /// Lowest corner, in voxels.
    pub origin: [u32; 3],
    /// Depth (the root is 0).
    pub depth: u32,
    /// Bit f set when face f has a tile.
    pub mask: u32,
    /// Whether a fold remained at the maximum depth.
    pub folded: bool,
}

/// One face of a leaf that carries a tile, with the triangles its texels may hit: those of
/// the face's cone overlapping its rectangle grown by one texel in the plane (the border
/// columns) and the leaf's slab grown by [`MARGIN`] voxels along the axis.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeafFace {
    /// Index of the leaf.
    pub leaf: u32,
    /// Face index (2·axis + (sign < 0)).
    pub face: u32,
    /// The columns the tile covers, border excluded: first column along the face's in-plane
    /// axes (b, c) relative to the leaf's origin, then width and height (≥ 1).
    pub rect: [u32; 4],
    /// Candidate triangles, ascending.
    pub triangles: Vec<u32>,
}

/// The refined tree.
pub struct Refined {
    /// Node cells, 8 per node (octant x | y << 1 | z << 2).
    pub nodes: Vec<u32>,
    /// The root's entry (a node pointer, a leaf, or 0 when nothing is stored).
    pub root: u32,
    /// Leaves in depth-first order.
    pub leaves: Vec<Leaf>,
    /// Faces with tiles, leaf by leaf, faces ascending.
    pub faces: Vec<LeafFace>,
}

struct Refiner<'a> {
    surface: &'a Surface,
    config: TileTreeConfig,
    resolution: u32,
    out: Refined,
}

/// Whether `t` overlaps the box [lo, hi] (grid units).
fn overlaps(surface: &Surface, t: u32, lo: Vec3, hi: Vec3) -> bool {
    triangle_box_overlap((lo + hi) * 0.5, (hi - lo) * 0.5, surface.vertices(t))
}

/// Builds the tree of `surface` (grid units) at equivalent resolution `resolution`.
pub fn refine(surface: &Surface, resolution: u32, config: TileTreeConfig) -> Refined {
    let mut r = Refiner {
        surface,
        config,
        resolution,
        out: Refined {
            nodes: Vec::new(),
            root: 0,
            leaves: Vec::new(),
            faces: Vec::new(),
        },
    };
    let all: Vec<u32> = (0..surface.triangles.len() as u32)
        .filter(|&t| surface.face[t as usize] != u32::MAX)
        .collect();
    r.out.root = r.node([0; 3], 0, all);
    r.out
}

impl Refiner<'_> {
    /// The entry of the node at `origin`, `depth`, given the triangles overlapping its box
    /// grown by [`MARGIN`].
    fn node(&mut self, origin: [u32; 3], depth: u32, near: Vec<u32>) -> u32 {
        let t = self.resolution >> depth;
        let lo = Vec3::from(origin.map(|c| c as f32));
        let hi = lo + t as f32;
        let inside: Vec<u32> = near
            .iter()
            .copied()
            .filter(|&i| overlaps(self.surface, i, lo, hi))
            .collect();
        let mut mask = 0u32;
        for &i in &inside {
            mask |= 1 << self.surface.face[i as usize];
        }
        if mask == 0 {
            return 0;
        }
        let can_split = t / 2 >= self.config.min_tile;
        let folded = t <= self.config.max_tile && self.has_fold(origin, t, mask, &inside);
        if can_split && (t > self.config.max_tile || folded) {
            let index = self.out.nodes.len() / 8;
            self.out.nodes.extend([0; 8]);
            let half = t / 2;
            for oct in 0..8u32 {
                let o = [0, 1, 2].map(|a| origin[a] + ((oct >> a) & 1) * half);
                let clo = Vec3::from(o.map(|c| c as f32)) - MARGIN;
                let chi = Vec3::from(o.map(|c| c as f32)) + half as f32 + MARGIN;
                let child_near: Vec<u32> = near
                    .iter()
                    .copied()
                    .filter(|&i| overlaps(self.surface, i, clo, chi))
                    .collect();
                let entry = self.node(o, depth + 1, child_near);
                self.out.nodes[8 * index + oct as usize] = entry;
            }
            return index as u32 + 1;
        }
        let leaf = self.out.leaves.len() as u32;
        let (mask, rects) = self.tiles(origin, t, mask, &inside);
        self.out.leaves.push(Leaf {
            origin,
            depth,
            mask,
            folded,
        });
        for (face, rect) in (0..6).zip(rects) {
            let Some(rect) = rect else {
                continue;
            };
            let (a, _) = face_axis(face);
            let (b, c) = plane_axes(a);
            let (mut glo, mut ghi) = (lo - MARGIN, hi + MARGIN);
            glo[b] = lo[b] + rect[0] as f32 - 1.0;
            ghi[b] = lo[b] + (rect[0] + rect[2]) as f32 + 1.0;
            glo[c] = lo[c] + rect[1] as f32 - 1.0;
            ghi[c] = lo[c] + (rect[1] + rect[3]) as f32 + 1.0;
            let triangles = near
                .iter()
                .copied()
                .filter(|&i| {
                    self.surface.cones[i as usize] & (1 << face) != 0
                        && overlaps(self.surface, i, glo, ghi)
                })
                .collect();
            self.out.faces.push(LeafFace {
                leaf,
                face,
                rect,
                triangles,
            });
        }
        LEAF_BIT | leaf
    }

    /// The faces a leaf keeps (a mask) and each one's rectangle of columns ([`LeafFace::rect`]),
    /// given its candidate faces `mask` and the triangles `inside` it.
    fn tiles(
        &self,
        origin: [u32; 3],
        t: u32,
        mask: u32,
        inside: &[u32],
    ) -> (u32, [Option<[u32; 4]>; 6]) {
        let surface = self.surface;
        let normals: Vec<Vec3> = inside
            .iter()
            .map(|&i| {
                let v = surface.vertices(i);
                (v[1] - v[0]).cross(v[2] - v[0])
            })
            .collect();
        let cones = |i: u32| surface.cones[i as usize] as u32;
        let mut count = [0usize; 6];
        for &i in inside {
            count[surface.face[i as usize] as usize] += 1;
        }
        let mut order: Vec<u32> = (0..6).filter(|f| mask & (1 << f) != 0).collect();
        order.sort_by_key(|&f| (count[f as usize], f));
        let mut kept = mask;
        for f in order {
            let others = kept & !(1 << f);
            if others == 0 {
                break;
            }
            let covered = inside
                .iter()
                .zip(&normals)
                .all(|(&i, &n)| pick_face(kept, n) != f || cones(i) & others != 0);
            if covered {
                kept = others;
            }
        }
        let score = |n: Vec3, f: u32| {
            let (a, s) = face_axis(f);
            s * n[a]
        };
        let mut rects: [Option<[u32; 4]>; 6] = [None; 6];
        for (&i, &n) in inside.iter().zip(&normals) {
            let pick = pick_face(kept, n);
            let floor = score(n, pick) - SWITCH_MARGIN * n.length();
            let v = surface.vertices(i);
            let (lo, hi) = (v[0].min(v[1]).min(v[2]), v[0].max(v[1]).max(v[2]));
            for f in 0..6 {
                let reads = f == pick || (cones(i) & (1 << f) != 0 && score(n, f) >= floor);
                if kept & (1 << f) == 0 || !reads {
                    continue;
                }
                let (a, _) = face_axis(f);
                let (b, c) = plane_axes(a);
                let column = |x: f32, axis: usize| {
                    (x - origin[axis] as f32).floor().clamp(0.0, t as f32 - 1.0) as u32
                };
                let (x0, y0) = (column(lo[b], b), column(lo[c], c));
                let (x1, y1) = (column(hi[b], b), column(hi[c], c));
                let r = rects[f as usize].get_or_insert([x0, y0, x1, y1]);
                *r = [r[0].min(x0), r[1].min(y0), r[2].max(x1), r[3].max(y1)];
            }
        }
        for r in rects.iter_mut().flatten() {
            *r = [r[0], r[1], r[2] - r[0] + 1, r[3] - r[1] + 1];
        }
        (kept, rects)
    }

    /// Whether a present face of the node sees two sheets over one texel column.
    fn has_fold(&self, origin: [u32; 3], t: u32, mask: u32, inside: &[u32]) -> bool {
        let n = (t * t) as usize;
        let mut low = vec![f32::INFINITY; n];
        let mut high = vec![f32::NEG_INFINITY; n];
        for face in 0..6 {
            if mask & (1 << face) == 0 {
                continue;
            }
            let (a, _) = face_axis(face);
            let (b, c) = plane_axes(a);
            low.fill(f32::INFINITY);
            high.fill(f32::NEG_INFINITY);
            let (za, zb) = (origin[a] as f32, (origin[a] + t) as f32);
            for &i in inside {
                if self.surface.cones[i as usize] & (1 << face) == 0 {
                    continue;
                }
                let v = self.surface.vertices(i);
                let range = |axis: usize| {
                    let lo = v[0][axis].min(v[1][axis]).min(v[2][axis]);
                    let hi = v[0][axis].max(v[1][axis]).max(v[2][axis]);
                    let o = origin[axis] as f32;
                    let first = (lo - 0.5 - o).ceil().max(0.0) as u32;
                    let last = ((hi - 0.5 - o).floor()).min(t as f32 - 1.0);
                    (first, last)
                };
                let (xb, xl) = range(b);
                let (yb, yl) = range(c);
                if xl < 0.0 || yl < 0.0 {
                    continue;
                }
                for y in yb..=yl as u32 {
                    for x in xb..=xl as u32 {
                        let cu = (origin[b] + x) as f32 + 0.5;
                        let cv = (origin[c] + y) as f32 + 0.5;
                        if let Some(h) = column_hit(v, a, cu, cv) {
                            if h >= za && h <= zb {
                                let k = (y * t + x) as usize;
                                low[k] = low[k].min(h);
                                high[k] = high[k].max(h);
                            }
                        }
                    }
                }
            }
            if low.iter().zip(&high).any(|(&l, &h)| h - l > FOLD_TOLERANCE) {
                return true;
            }
        }
        false
    }
}
