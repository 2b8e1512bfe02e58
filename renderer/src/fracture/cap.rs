//! Triangulation of a cross-section ("cap") with spade's constrained Delaunay triangulation.
//!
//! The cut segments are inserted as constraint edges and every triangle of the CDT gets the
//! winding number of the segments around it by a flood fill that changes the winding when it
//! crosses a segment. This needs no chaining of loops, so nested loops (holes, islands in
//! holes) and loops touching at a vertex need no special cases, and the cap uses exactly the
//! segment end points, so it closes the surface without T-junctions.
//!
//! A surface that intersects itself (common in scans) gives cut segments that cross, or loops
//! that overlap. Then the cap is built by [`resolve`]: a vertex is inserted where two segments
//! cross (the surface edges are split there too, so the two sheets meet at it), and the
//! winding function is split into layers, `{w ≤ -k}` and `{w ≥ k}`, each triangulated on its
//! own. Every unit of segment bounds exactly one layer, so every edge stays balanced (used as
//! often in each direction) and the pieces keep the input's winding-weighted volume; where
//! two layers lie over each other, as the two sheets do in the input, they may share an edge.

use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
use std::collections::{HashMap, HashSet, VecDeque};

/// A vertex the cap adds: on the line from `from` to `to` at parameter `t` (both ends are
/// vertex ids the caller can place, possibly earlier new vertices).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct NewVertex {
    pub id: u32,
    pub from: u32,
    pub to: u32,
    pub t: f64,
}

/// A triangulated cap, in the caller's vertex ids.
#[derive(Debug, Default)]
pub(crate) struct Cap {
    /// Triangles counter-clockwise in the 2D frame (which faces the segments' "below" side).
    pub triangles: Vec<[u32; 3]>,
    /// Segments `(u, v)` whose line passes exactly through other cap vertices, or that cross
    /// other segments, with those vertices in order from `u` to `v`: the surface edge must be
    /// split the same way.
    pub splits: Vec<((u32, u32), Vec<u32>)>,
    /// Vertices `(id, kept)` with the same 2D position as `kept`; `id` must be replaced by
    /// `kept` everywhere.
    pub welds: Vec<(u32, u32)>,
    /// Vertices the cap made where segments cross, ids from the caller's
    /// `first_new` on, in id order.
    pub new_vertices: Vec<NewVertex>,
    /// How many crossings of cut segments were resolved (0 unless the surface intersects
    /// itself in this plane).
    pub crossings: usize,
}

/// Why the plain triangulation failed.
enum Failure {
    /// Segments cross or loops overlap: the surface intersects itself; [`resolve`] handles it.
    SelfIntersection,
    /// Anything else (open loops, a point spade refuses).
    Other(String),
}

/// Most rounds of crossing detection: a crossing point can land next to a third segment and
/// make a new crossing with it, which the next round resolves.
const CROSSING_ROUNDS: usize = 4;
/// A crossing closer than this (relative to the coordinates' magnitude) to a piece's end is
/// taken to be at that end.
const SNAP: f64 = 1e-9;

/// Triangulates the region bounded by the directed `segments`: the region where the segments
/// wind clockwise (winding number -1), i.e. to the right of each segment, which is where the
/// solid lies when the segments are the boundary edges of the part below the plane. Crossing
/// segments and overlapping loops (a self-intersecting surface) are resolved (module docs);
/// new vertices get ids from `first_new` on.
///
/// `point` gives the 2D position of a vertex id.
///
/// # Errors
/// A message when the segments do not form closed loops, or a self-intersection cannot be
/// resolved (degenerate crossings that spade refuses).
pub(crate) fn triangulate(
    segments: &[(u32, u32)],
    point: impl Fn(u32) -> [f64; 2],
    first_new: u32,
) -> Result<Cap, String> {
    if segments.is_empty() {
        return Ok(Cap::default());
    }
    // Every vertex must have as many segments in as out, or the loops are open.
    let mut balance: HashMap<u32, i32> = HashMap::new();
    for &(u, v) in segments {
        *balance.entry(u).or_default() += 1;
        *balance.entry(v).or_default() -= 1;
    }
    let open = balance.values().filter(|&&b| b != 0).count();
    if open > 0 {
        return Err(format!(
            "cut segments do not form closed loops ({open} open end(s))"
        ));
    }
    let plain = Arrangement::build(segments, &point).and_then(|a| {
        let winding = a.windings()?;
        if winding.iter().flatten().any(|w| w.abs() > 1) {
            return Err(Failure::SelfIntersection);
        }
        Ok(a.into_cap(&winding))
    });
    match plain {
        Ok(cap) => Ok(cap),
        Err(Failure::Other(message)) => Err(message),
        Err(Failure::SelfIntersection) => resolve(segments, &point, first_new),
    }
}

/// The cap of a self-intersecting cross-section: weld, split crossing segments, find each
/// segment's layer from the windings of one CDT of all segments, then triangulate every layer
/// on its own.
fn resolve(
    segments: &[(u32, u32)],
    point: &dyn Fn(u32) -> [f64; 2],
    first_new: u32,
) -> Result<Cap, String> {
    let mut cap = Cap::default();
    // Weld as spade would: one id per exact 2D position, the first in segment order.
    let mut at: HashMap<[u64; 2], u32> = HashMap::new();
    let mut weld: HashMap<u32, u32> = HashMap::new();
    for &id in segments.iter().flat_map(|(u, v)| [u, v]) {
        let p = point(id);
        let kept = *at.entry([p[0].to_bits(), p[1].to_bits()]).or_insert(id);
        if kept != id && weld.insert(id, kept).is_none() {
            cap.welds.push((id, kept));
        }
    }
    let welded = |id: u32| weld.get(&id).copied().unwrap_or(id);

    // Split crossing segments, round by round. `new_points` holds the new vertices' 2D
    // positions; each piece remembers the (welded) input segment it lies on, and a segment's
    // pieces stay consecutive and in order along it.
    let mut new_points: Vec<[f64; 2]> = Vec::new();
    let mut pieces: Vec<(u32, u32, usize)> = segments
        .iter()
        .enumerate()
        .map(|(o, &(u, v))| (welded(u), welded(v), o))
        .filter(|(u, v, _)| u != v)
        .collect();
    for _ in 0..CROSSING_ROUNDS {
        let found = {
            let pos = |id: u32| pos_of(id, &new_points, first_new, point);
            let ends: Vec<(u32, u32)> = pieces.iter().map(|&(u, v, _)| (u, v)).collect();
            crossings(&ends, &pos)
        };
        if found.is_empty() {
            break;
        }
        // Per undirected piece: (t from its lower id, new id).
        let mut on: HashMap<(u32, u32), Vec<(f64, u32)>> = HashMap::new();
        for c in &found {
            let at = |id: u32| pos_of(id, &new_points, first_new, point);
            let (pa, pb) = (at(c.a.0), at(c.a.1));
            let x = [
                pa[0] + (pb[0] - pa[0]) * c.ta,
                pa[1] + (pb[1] - pa[1]) * c.ta,
            ];
            // A crossing (numerically) at an end of one piece is that end lying on the other
            // piece: split the other there rather than add a vertex on top of the end.
            let scale = [pa, pb, at(c.b.0), at(c.b.1)]
                .iter()
                .fold(0.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()))
                .max(f64::MIN_POSITIVE);
            let near = |id: u32| {
                let p = at(id);
                (p[0] - x[0]).hypot(p[1] - x[1]) <= SNAP * scale
            };
            if let Some(&end) = [c.a.0, c.a.1].iter().find(|&&e| near(e)) {
                on.entry(c.b).or_default().push((c.tb, end));
            } else if let Some(&end) = [c.b.0, c.b.1].iter().find(|&&e| near(e)) {
                on.entry(c.a).or_default().push((c.ta, end));
            } else {
                let id = first_new + cap.new_vertices.len() as u32;
                new_points.push(x);
                cap.new_vertices.push(NewVertex {
                    id,
                    from: c.a.0,
                    to: c.a.1,
                    t: c.ta,
                });
                on.entry(c.a).or_default().push((c.ta, id));
                on.entry(c.b).or_default().push((c.tb, id));
            }
        }
        cap.crossings += found.len();
        let mut next = Vec::with_capacity(pieces.len() + 2 * found.len());
        for &(u, v, o) in &pieces {
            let Some(list) = on.get_mut(&undirected(u, v)) else {
                next.push((u, v, o));
                continue;
            };
            list.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            let mut chain: Vec<u32> = list.iter().map(|&(_, id)| id).collect();
            if u > v {
                chain.reverse();
            }
            let mut prev = u;
            for &x in &chain {
                next.push((prev, x, o));
                prev = x;
            }
            next.push((prev, v, o));
        }
        pieces = next;
    }
    let pos = |id: u32| pos_of(id, &new_points, first_new, point);
    let ends: Vec<(u32, u32)> = pieces.iter().map(|&(u, v, _)| (u, v)).collect();
    let all = Arrangement::build(&ends, &pos).map_err(|f| match f {
        Failure::SelfIntersection => "cut segments cross and could not be split (degenerate crossings): the surface intersects itself there".to_string(),
        Failure::Other(m) => m,
    })?;
    // Crossing points that still coincide with another vertex are welded like input vertices.
    cap.welds.extend(all.welds.iter().copied());
    let winding = all.windings().map_err(|_| {
        "cut loops are inconsistent after resolving crossings (winding differs around a vertex)"
            .to_string()
    })?;

    // The surface edges' splits: per input segment (keyed by its own ids, since the caller
    // splits before it welds), the vertices on its pieces and the pieces' inner ends.
    let on_piece: HashMap<(u32, u32), Vec<u32>> = all.splits.iter().cloned().collect();
    let mut chains: Vec<Vec<u32>> = vec![Vec::new(); segments.len()];
    for (k, &(u, v, o)) in pieces.iter().enumerate() {
        if let Some(inner) = on_piece.get(&(u, v)) {
            chains[o].extend(inner.iter().copied());
        }
        if pieces.get(k + 1).is_some_and(|next| next.2 == o) {
            chains[o].push(v);
        }
    }
    let mut seen: HashSet<(u32, u32)> = HashSet::new();
    for (o, chain) in chains.into_iter().enumerate() {
        if !chain.is_empty() && seen.insert(segments[o]) {
            cap.splits.push((segments[o], chain));
        }
    }

    // Layers: a unit of segment with winding w on its right and w + 1 on its left bounds
    // {winding <= w} (layer w, for w < 0) or {winding >= w + 1} (layer w + 1, for w >= 0).
    let mut layers: HashMap<i32, Vec<(u32, u32)>> = HashMap::new();
    for (&(lo, hi), &n) in &all.net {
        if n == 0 {
            continue;
        }
        let (a, b) = if n > 0 { (lo, hi) } else { (hi, lo) };
        let Some(right) = all.winding_right_of(a, b, &winding) else {
            return Err("a cut segment lies on the hull with no face beside it".into());
        };
        for k in 0..n.abs() {
            let w = right + k;
            let layer = if w < 0 { w } else { w + 1 };
            layers
                .entry(layer)
                .or_default()
                .push((all.owner[a], all.owner[b]));
        }
    }
    let mut order: Vec<i32> = layers.keys().copied().collect();
    order.sort_by_key(|&l| (-l.abs(), l));
    for l in order {
        let mut edges = layers.remove(&l).unwrap_or_default();
        edges.sort_unstable(); // HashMap order must not decide the triangulation
        let layer = Arrangement::build(&edges, &pos).map_err(|f| match f {
            Failure::SelfIntersection => format!("cap layer {l} could not be triangulated"),
            Failure::Other(m) => m,
        })?;
        let w = layer
            .windings()
            .map_err(|_| format!("cap layer {l}: inconsistent winding"))?;
        cap.triangles.extend(layer.faces(&w));
    }
    Ok(cap)
}

fn undirected(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The 2D position of `id` in [`resolve`]: an input vertex or a crossing.
fn pos_of(
    id: u32,
    new_points: &[[f64; 2]],
    first_new: u32,
    point: &dyn Fn(u32) -> [f64; 2],
) -> [f64; 2] {
    if id < first_new {
        point(id)
    } else {
        new_points[(id - first_new) as usize]
    }
}

/// A proper crossing of two undirected pieces `a` and `b` (keys `(lower id, higher id)`), at
/// parameter `ta` along `a` and `tb` along `b`, both measured from the lower id.
struct Crossing {
    a: (u32, u32),
    b: (u32, u32),
    ta: f64,
    tb: f64,
}

/// Proper crossings (interiors crossing at one point) between the pieces, found by a sweep
/// over x. Touching (an end on another piece) and collinear overlaps are left to the CDT.
fn crossings(pieces: &[(u32, u32)], pos: &dyn Fn(u32) -> [f64; 2]) -> Vec<Crossing> {
    let mut keys: Vec<(u32, u32)> = pieces.iter().map(|&(u, v)| undirected(u, v)).collect();
    keys.sort_unstable();
    keys.dedup();
    let ends: Vec<([f64; 2], [f64; 2])> = keys.iter().map(|&(a, b)| (pos(a), pos(b))).collect();
    let mut by_x: Vec<usize> = (0..keys.len()).collect();
    let lo_x = |i: usize| ends[i].0[0].min(ends[i].1[0]);
    let hi_x = |i: usize| ends[i].0[0].max(ends[i].1[0]);
    by_x.sort_by(|&i, &j| lo_x(i).total_cmp(&lo_x(j)).then(i.cmp(&j)));
    let orient = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    };
    let mut out = Vec::new();
    for (n, &i) in by_x.iter().enumerate() {
        let (p, q) = ends[i];
        for &j in &by_x[n + 1..] {
            if lo_x(j) > hi_x(i) {
                break;
            }
            let (ka, kb) = (keys[i], keys[j]);
            if ka.0 == kb.0 || ka.0 == kb.1 || ka.1 == kb.0 || ka.1 == kb.1 {
                continue; // pieces sharing an end meet there
            }
            let (r, s) = ends[j];
            let (o1, o2) = (orient(p, q, r), orient(p, q, s));
            let (o3, o4) = (orient(r, s, p), orient(r, s, q));
            if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                out.push(Crossing {
                    a: ka,
                    b: kb,
                    ta: o3 / (o3 - o4),
                    tb: o1 / (o1 - o2),
                });
            }
        }
    }
    // Deterministic order (the sweep's is, but keys make it independent of ties).
    out.sort_by_key(|x| (x.a, x.b));
    out
}

/// One CDT of some directed segments with the net number of segments along each of its
/// edges: what the winding numbers and the triangles are computed from.
struct Arrangement {
    cdt: ConstrainedDelaunayTriangulation<Point2<f64>>,
    /// spade vertex index -> caller id.
    owner: Vec<u32>,
    handle_of: HashMap<u32, FixedVertexHandle>,
    /// Net number of segments along each CDT edge, keyed (lower handle, higher handle),
    /// positive when running from the lower to the higher handle.
    net: HashMap<(usize, usize), i32>,
    /// As [`Cap::splits`].
    splits: Vec<((u32, u32), Vec<u32>)>,
    /// As [`Cap::welds`].
    welds: Vec<(u32, u32)>,
}

impl Arrangement {
    /// Inserts the segments' ends, then the segments as constraints.
    fn build(
        segments: &[(u32, u32)],
        point: &dyn Fn(u32) -> [f64; 2],
    ) -> Result<Arrangement, Failure> {
        let mut a = Arrangement {
            cdt: ConstrainedDelaunayTriangulation::new(),
            owner: Vec::new(),
            handle_of: HashMap::new(),
            net: HashMap::new(),
            splits: Vec::new(),
            welds: Vec::new(),
        };
        let ids = segments
            .iter()
            .flat_map(|(u, v)| [*u, *v])
            .map(|id| (id, point(id)));
        for (id, [x, y]) in ids {
            if a.handle_of.contains_key(&id) {
                continue;
            }
            let p = spade::mitigate_underflow(Point2::new(x, y));
            let h = a.cdt.insert(p).map_err(|e| {
                Failure::Other(format!(
                    "cannot insert cut vertex {id} at ({x}, {y}): {e:?}"
                ))
            })?;
            if h.index() < a.owner.len() {
                // Same 2D position as an earlier vertex: spade keeps one, so must the surface.
                a.welds.push((id, a.owner[h.index()]));
            } else {
                a.owner.push(id);
            }
            a.handle_of.insert(id, h);
        }
        for &(u, v) in segments {
            let (hu, hv) = (a.handle_of[&u], a.handle_of[&v]);
            if hu == hv {
                continue; // zero length after welding
            }
            let edges = a.cdt.try_add_constraint(hu, hv);
            if edges.is_empty() {
                return Err(Failure::SelfIntersection);
            }
            let pu = a.cdt.vertex(hu).position();
            let dir = [
                a.cdt.vertex(hv).position().x - pu.x,
                a.cdt.vertex(hv).position().y - pu.y,
            ];
            let cdt = &a.cdt;
            let along = |h: FixedVertexHandle| {
                let p = cdt.vertex(h).position();
                (p.x - pu.x) * dir[0] + (p.y - pu.y) * dir[1]
            };
            let mut pieces: Vec<(f64, FixedVertexHandle, FixedVertexHandle)> = edges
                .iter()
                .map(|&e| {
                    let [p, q] = cdt.directed_edge(e).vertices().map(|v| v.fix());
                    if along(p) <= along(q) {
                        (along(p), p, q)
                    } else {
                        (along(q), q, p)
                    }
                })
                .collect();
            pieces.sort_by(|x, y| x.0.total_cmp(&y.0));
            for &(_, p, q) in &pieces {
                let (lo, hi, sign) = if p.index() < q.index() {
                    (p, q, 1)
                } else {
                    (q, p, -1)
                };
                *a.net.entry((lo.index(), hi.index())).or_default() += sign;
            }
            if pieces.len() > 1 {
                let chain = pieces[1..]
                    .iter()
                    .map(|&(_, p, _)| a.owner[p.index()])
                    .collect();
                a.splits.push(((u, v), chain));
            }
        }
        Ok(a)
    }

    fn net_along(&self, a: usize, b: usize) -> i32 {
        if a < b {
            self.net.get(&(a, b)).copied().unwrap_or(0)
        } else {
            -self.net.get(&(b, a)).copied().unwrap_or(0)
        }
    }

    /// Winding number per face (index = spade face index) by a flood fill from the hull; the
    /// outer face has winding 0 and a face to the left of a segment has winding one more than
    /// the face to its right.
    fn windings(&self) -> Result<Vec<Option<i32>>, Failure> {
        let cdt = &self.cdt;
        let mut winding: Vec<Option<i32>> = vec![None; cdt.num_all_faces()];
        let mut queue = VecDeque::new();
        for face in cdt.inner_faces() {
            for e in face.adjacent_edges() {
                if e.rev().face().is_outer() {
                    let w = self.net_along(e.from().fix().index(), e.to().fix().index());
                    let slot = &mut winding[face.fix().index()];
                    match *slot {
                        None => {
                            *slot = Some(w);
                            queue.push_back(face.fix());
                        }
                        Some(old) if old != w => {
                            return Err(Failure::Other("inconsistent winding at the hull".into()))
                        }
                        Some(_) => {}
                    }
                }
            }
        }
        while let Some(f) = queue.pop_front() {
            let w = winding[f.index()].unwrap_or(0);
            for e in cdt.face(f).adjacent_edges() {
                let right = e.rev().face();
                let Some(g) = right.as_inner().map(|g| g.fix()) else {
                    continue;
                };
                let wg = w - self.net_along(e.from().fix().index(), e.to().fix().index());
                match winding[g.index()] {
                    None => {
                        winding[g.index()] = Some(wg);
                        queue.push_back(g);
                    }
                    Some(old) if old != wg => {
                        return Err(Failure::Other(
                            "cut loops are inconsistent (winding differs around a vertex)".into(),
                        ));
                    }
                    Some(_) => {}
                }
            }
        }
        Ok(winding)
    }

    /// The winding of the face to the right of the CDT edge from handle index `a` to `b`
    /// (0 outside the hull).
    fn winding_right_of(&self, a: usize, b: usize, winding: &[Option<i32>]) -> Option<i32> {
        let (ha, hb) = (
            self.handle_of[&self.owner[a]],
            self.handle_of[&self.owner[b]],
        );
        let e = self.cdt.get_edge_from_neighbors(ha, hb)?;
        // `e` runs from a to b with its face on the left; the right face is the reverse's.
        Some(match e.rev().face().as_inner() {
            Some(f) => winding[f.fix().index()].unwrap_or(0),
            None => 0,
        })
    }

    /// The faces with winding ±1, counter-clockwise for -1 (the region right of the segments)
    /// and reversed for +1 (an inside-out region), in caller ids.
    fn faces(&self, winding: &[Option<i32>]) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        for face in self.cdt.inner_faces() {
            let w = winding[face.fix().index()].unwrap_or(0);
            if w == 0 {
                continue;
            }
            let [a, b, c] = face.vertices().map(|v| self.owner[v.fix().index()]);
            out.push(if w < 0 { [a, b, c] } else { [a, c, b] });
        }
        out
    }

    /// The plain cap: faces with winding ±1 (the caller checked that no face winds more).
    fn into_cap(self, winding: &[Option<i32>]) -> Cap {
        Cap {
            triangles: self.faces(winding),
            splits: self.splits,
            welds: self.welds,
            new_vertices: Vec::new(),
            crossings: 0,
        }
    }
}
