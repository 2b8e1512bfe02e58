//! Separating the sheets of a closed piece where they meet, so that every piece is a closed
//! 2-manifold: tools that cook physics, check watertightness or run booleans reject an edge
//! used by four triangles or a vertex where two sheets touch, though such a surface is closed.
//!
//! A piece of a self-intersecting input gets both where a cut runs through a double cap (two
//! layers of one cross-section, `cap::resolve`). The triangles at such an edge are paired
//! into sheets by the solid wedges between them (below), every vertex then gets one copy per
//! fan of triangles that the pairing connects around it, and an edge whose two sheets still
//! share both ends after that is split at its midpoint, once per extra sheet. Positions do
//! not move (a copy sits where the vertex was), so the volume and the texture lookups at
//! rest-pose positions are unchanged; the pieces still intersect themselves where the input
//! does.

use super::Fragment;
use std::collections::HashMap;

/// How many vertex copies [`separate_sheets`] made and how many edges it split.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Separated {
    pub vertices: usize,
    pub edges: usize,
}

/// One use of an undirected edge (lo < hi) by a triangle.
#[derive(Clone, Copy)]
struct Use {
    triangle: usize,
    /// `true` when the triangle runs lo -> hi.
    forward: bool,
    /// Angle of the triangle's third vertex about the edge (see [`pair_by_wedges`]).
    angle: f64,
}

/// Makes `piece` edge- and vertex-manifold in place (see the module docs). `piece` must be
/// closed and consistently oriented (every edge used as often in each direction), which every
/// cut guarantees; an edge that is not is left as it is.
pub(crate) fn separate_sheets(piece: &mut Fragment) -> Separated {
    let pairs = pair_edges(piece);
    let original = piece.triangles.clone();
    let mut separated = Separated::default();
    // Corners 3t + k; the pairs across an edge join the two triangles' corners at each end.
    let mut fans = UnionFind::new(piece.triangles.len() * 3);
    let corner = |t: usize, v: u32, tris: &[[u32; 3]]| {
        3 * t + tris[t].iter().position(|&i| i == v).expect("edge vertex")
    };
    for &(s, t, a, b) in &pairs {
        for v in [a, b] {
            fans.union(
                corner(s, v, &piece.triangles),
                corner(t, v, &piece.triangles),
            );
        }
    }
    // The first fan met at a vertex keeps it; every further fan gets a copy.
    let mut owner: Vec<Option<usize>> = vec![None; piece.positions.len()];
    let mut copies: HashMap<usize, u32> = HashMap::new();
    for t in 0..piece.triangles.len() {
        for k in 0..3 {
            let v = piece.triangles[t][k] as usize;
            let root = fans.find(3 * t + k);
            match owner[v] {
                None => owner[v] = Some(root),
                Some(r) if r == root => {}
                Some(_) => {
                    let copy = *copies.entry(root).or_insert_with(|| {
                        piece.positions.push(piece.positions[v]);
                        separated.vertices += 1;
                        piece.positions.len() as u32 - 1
                    });
                    piece.triangles[t][k] = copy;
                }
            }
        }
    }
    separated.edges = split_shared_edges(piece, &pairs, &original);
    separated
}

/// Pairs every use of an edge in one direction with one in the other, as triangle pairs
/// `(s, t, a, b)` where `s` runs a -> b and `t` runs b -> a.
fn pair_edges(piece: &Fragment) -> Vec<(usize, usize, u32, u32)> {
    let mut uses: Vec<(u64, usize, bool)> = Vec::with_capacity(piece.triangles.len() * 3);
    for (t, tri) in piece.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (lo, hi) = (a.min(b), a.max(b));
            uses.push(((u64::from(lo) << 32) | u64::from(hi), t, a < b));
        }
    }
    uses.sort_unstable();
    let mut pairs = Vec::with_capacity(uses.len() / 2);
    let mut start = 0;
    while start < uses.len() {
        let key = uses[start].0;
        let end = start + uses[start..].iter().take_while(|u| u.0 == key).count();
        let (lo, hi) = ((key >> 32) as u32, key as u32);
        let group = &uses[start..end];
        let forward = group.iter().filter(|u| u.2).count();
        if 2 * forward == group.len() {
            if group.len() == 2 {
                let (f, b) = if group[0].2 {
                    (group[0], group[1])
                } else {
                    (group[1], group[0])
                };
                pairs.push((f.1, b.1, lo, hi));
            } else {
                let around = group
                    .iter()
                    .map(|&(_, triangle, forward)| Use {
                        triangle,
                        forward,
                        angle: angle_about(piece, triangle, lo, hi),
                    })
                    .collect();
                for (f, b) in pair_by_wedges(around) {
                    pairs.push((f, b, lo, hi));
                }
            }
        }
        start = end;
    }
    pairs
}

/// Angle of triangle `t`'s third vertex about the edge lo -> hi, in a frame (x, y) with
/// x × y along the edge.
fn angle_about(piece: &Fragment, t: usize, lo: u32, hi: u32) -> f64 {
    let p = |i: u32| piece.positions[i as usize].as_dvec3();
    let third = piece.triangles[t]
        .into_iter()
        .find(|&i| i != lo && i != hi)
        .expect("triangle with three vertices");
    let d = (p(hi) - p(lo)).normalize_or_zero();
    let x = d.any_orthonormal_vector();
    let y = d.cross(x);
    let u = p(third) - p(lo);
    u.dot(y).atan2(u.dot(x))
}

/// Pairs the uses of one edge by the wedges of solid between them. A triangle running
/// lo -> hi has its outward normal a quarter turn ahead of its angle (x × y points along the
/// edge), so the solid lies just behind it; one running hi -> lo has the solid just ahead.
/// Going around the edge, a reverse use opens a wedge of solid and a forward use closes it:
/// the pairs are the matched brackets of that cyclic sequence, started after its deepest
/// point so that every bracket closes. At equal angles a closing use comes first, so two
/// coincident faces of opposite sides are not paired into a wedge of no volume.
fn pair_by_wedges(mut around: Vec<Use>) -> Vec<(usize, usize)> {
    around.sort_by(|a, b| {
        a.angle
            .total_cmp(&b.angle)
            .then(b.forward.cmp(&a.forward))
            .then(a.triangle.cmp(&b.triangle))
    });
    let (mut depth, mut lowest, mut start) = (0i64, 0i64, 0);
    for (i, u) in around.iter().enumerate() {
        depth += if u.forward { -1 } else { 1 };
        if depth < lowest {
            lowest = depth;
            start = i + 1;
        }
    }
    let mut open = Vec::new();
    let mut pairs = Vec::with_capacity(around.len() / 2);
    for i in 0..around.len() {
        let u = around[(start + i) % around.len()];
        if u.forward {
            let opener: Use = open.pop().expect("balanced uses");
            pairs.push((u.triangle, opener.triangle));
        } else {
            open.push(u);
        }
    }
    pairs
}

/// Splits at its midpoint, once per sheet after the first, every edge still used by more than
/// two triangles after the vertex copies (its sheets meet around both ends elsewhere), so that
/// each sheet gets an edge of its own. The sheets are the pairs the copies were made from: a
/// new pairing of what is left at the edge could join the triangles around a vertex
/// differently from its copy. `original` holds the triangles before the copies renamed their
/// vertices. Returns how many edges were split.
fn split_shared_edges(
    piece: &mut Fragment,
    pairs: &[(usize, usize, u32, u32)],
    original: &[[u32; 3]],
) -> usize {
    let renamed = |piece: &Fragment, t: usize, v: u32| {
        let k = original[t]
            .iter()
            .position(|&i| i == v)
            .expect("edge vertex");
        piece.triangles[t][k]
    };
    // Pairs by the edge they run after the copies, seen from the triangle that runs it a -> b.
    let mut by_edge: Vec<((u32, u32), usize, usize)> = pairs
        .iter()
        .map(|&(s, t, a, b)| ((renamed(piece, s, a), renamed(piece, s, b)), s, t))
        .collect();
    by_edge.sort_unstable();
    // What each original triangle has become: itself, and the halves later splits pushed.
    let mut halves: HashMap<usize, Vec<usize>> = HashMap::new();
    let mut splits = 0;
    for group in by_edge.chunk_by(|x, y| x.0 == y.0) {
        let (a, b) = group[0].0;
        for &(_, s, t) in &group[1..] {
            let holding = |piece: &Fragment, halves: &HashMap<usize, Vec<usize>>, tri, from, to| {
                std::iter::once(tri)
                    .chain(halves.get(&tri).into_iter().flatten().copied())
                    .find(|&x| {
                        let v = piece.triangles[x];
                        (0..3).any(|k| v[k] == from && v[(k + 1) % 3] == to)
                    })
                    .expect("a half holds the edge")
            };
            let (hs, ht) = (
                holding(piece, &halves, s, a, b),
                holding(piece, &halves, t, b, a),
            );
            let first_new = piece.triangles.len();
            split_pair(piece, hs, ht, a, b);
            halves.entry(s).or_default().push(first_new);
            halves.entry(t).or_default().push(first_new + 1);
            splits += 1;
        }
    }
    splits
}

/// Splits the edge a–b that triangles `s` and `t` share (one runs it each way) at a new
/// midpoint vertex of their own, each triangle into two (the second halves are pushed, `s`'s
/// first).
fn split_pair(piece: &mut Fragment, s: usize, t: usize, a: u32, b: u32) {
    let mid =
        (piece.positions[a as usize].as_dvec3() + piece.positions[b as usize].as_dvec3()) * 0.5;
    let m = piece.positions.len() as u32;
    piece.positions.push(mid.as_vec3());
    for tri in [s, t] {
        let old = piece.triangles[tri];
        let j = (0..3)
            .find(|&j| {
                let (x, y) = (old[j], old[(j + 1) % 3]);
                (x, y) == (a, b) || (x, y) == (b, a)
            })
            .expect("the shared edge");
        let (from, to, third) = (old[j], old[(j + 1) % 3], old[(j + 2) % 3]);
        piece.triangles[tri] = [from, m, third];
        piece.triangles.push([m, to, third]);
        let flag = piece.interior[tri];
        piece.interior.push(flag);
    }
}

/// Disjoint sets over corners, with path halving.
struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            // The smaller root wins, so the result does not depend on the order of unions.
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.parent[hi] = lo;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Two pairs of triangles at one edge whose ends the vertex copies could not tell apart
    /// (both sheets' fans are joined around both ends elsewhere): the second pair gets a
    /// midpoint of its own, and no directed edge is used twice afterwards.
    #[test]
    fn an_edge_two_sheets_still_share_is_split() {
        let (a, b) = (0, 1);
        let mut piece = Fragment {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z],
            triangles: vec![[a, b, 2], [b, a, 3], [a, b, 4], [b, a, 5]],
            interior: vec![false, true, false, true],
            ..Fragment::default()
        };
        let pairs = [(0, 1, a, b), (2, 3, a, b)];
        let original = piece.triangles.clone();
        assert_eq!(split_shared_edges(&mut piece, &pairs, &original), 1);
        assert_eq!(piece.triangles.len(), 6);
        assert_eq!(piece.interior, [false, true, false, true, false, true]);
        assert_eq!(piece.positions[6], Vec3::new(0.5, 0.0, 0.0));
        let mut directed: Vec<(u32, u32)> = piece
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .collect();
        let n = directed.len();
        directed.sort_unstable();
        directed.dedup();
        assert_eq!(directed.len(), n, "{:?}", piece.triangles);
    }
}
