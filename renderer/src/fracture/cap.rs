//! Triangulation of a cross-section ("cap") with spade's constrained Delaunay triangulation.
//!
//! The cut segments are inserted as constraint edges and every triangle of the CDT gets the
//! winding number of the segments around it by a flood fill that changes the winding when it
//! crosses a segment. This needs no chaining of loops, so nested loops (holes, islands in
//! holes) and loops touching at a vertex need no special cases, and the cap uses exactly the
//! segment end points, so it closes the surface without T-junctions.

use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};
use std::collections::{HashMap, VecDeque};

/// A triangulated cap, in the caller's vertex ids.
#[derive(Debug, Default)]
pub(crate) struct Cap {
    /// Triangles counter-clockwise in the 2D frame (which faces the segments' "below" side).
    pub triangles: Vec<[u32; 3]>,
    /// Segments `(u, v)` whose line passes exactly through other cap vertices, with those
    /// vertices in order from `u` to `v`: the surface edge must be split the same way.
    pub splits: Vec<((u32, u32), Vec<u32>)>,
    /// Vertices `(id, kept)` with the same 2D position as `kept`; `id` must be replaced by
    /// `kept` everywhere.
    pub welds: Vec<(u32, u32)>,
}

/// Triangulates the region bounded by the directed `segments`: the region where the segments
/// wind clockwise (winding number -1), i.e. to the right of each segment, which is where the
/// solid lies when the segments are the boundary edges of the part below the plane.
///
/// `point` gives the 2D position of a vertex id.
///
/// # Errors
/// A message when the segments do not form closed loops, cross each other, or wind more than
/// once around some point (self-intersecting surface).
pub(crate) fn triangulate(
    segments: &[(u32, u32)],
    point: impl Fn(u32) -> [f64; 2],
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

    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::new();
    let mut handle_of: HashMap<u32, FixedVertexHandle> = HashMap::new();
    let mut owner: Vec<u32> = Vec::new(); // spade vertex index -> caller id
    let mut cap = Cap::default();
    for &id in segments.iter().flat_map(|(u, v)| [u, v]) {
        if handle_of.contains_key(&id) {
            continue;
        }
        let [x, y] = point(id);
        let p = spade::mitigate_underflow(Point2::new(x, y));
        let h = cdt
            .insert(p)
            .map_err(|e| format!("cannot insert cut vertex {id} at ({x}, {y}): {e:?}"))?;
        if h.index() < owner.len() {
            // Same 2D position as an earlier vertex: spade keeps one, so must the surface.
            cap.welds.push((id, owner[h.index()]));
        } else {
            owner.push(id);
        }
        handle_of.insert(id, h);
    }

    // Net number of segments along each CDT edge, keyed (lower handle, higher handle),
    // positive when running from the lower to the higher handle.
    let mut net: HashMap<(usize, usize), i32> = HashMap::new();
    for &(u, v) in segments {
        let (hu, hv) = (handle_of[&u], handle_of[&v]);
        if hu == hv {
            continue; // zero length after welding
        }
        let edges = cdt.try_add_constraint(hu, hv);
        if edges.is_empty() {
            let [x, y] = point(u);
            return Err(format!(
                "cut segments cross near ({x:.6}, {y:.6}) in the plane: the surface intersects itself there"
            ));
        }
        let pu = cdt.vertex(hu).position();
        let dir = [
            cdt.vertex(hv).position().x - pu.x,
            cdt.vertex(hv).position().y - pu.y,
        ];
        let along = |h: FixedVertexHandle| {
            let p = cdt.vertex(h).position();
            (p.x - pu.x) * dir[0] + (p.y - pu.y) * dir[1]
        };
        let mut pieces: Vec<(f64, FixedVertexHandle, FixedVertexHandle)> = edges
            .iter()
            .map(|&e| {
                let [a, b] = cdt.directed_edge(e).vertices().map(|v| v.fix());
                if along(a) <= along(b) {
                    (along(a), a, b)
                } else {
                    (along(b), b, a)
                }
            })
            .collect();
        pieces.sort_by(|x, y| x.0.total_cmp(&y.0));
        for &(_, a, b) in &pieces {
            let (lo, hi, sign) = if a.index() < b.index() {
                (a, b, 1)
            } else {
                (b, a, -1)
            };
            *net.entry((lo.index(), hi.index())).or_default() += sign;
        }
        if pieces.len() > 1 {
            let chain = pieces[1..]
                .iter()
                .map(|&(_, a, _)| owner[a.index()])
                .collect();
            cap.splits.push(((u, v), chain));
        }
    }
    let net_along = |a: usize, b: usize| -> i32 {
        if a < b {
            net.get(&(a, b)).copied().unwrap_or(0)
        } else {
            -net.get(&(b, a)).copied().unwrap_or(0)
        }
    };

    // Flood fill of winding numbers; the outer face has winding 0 and a face to the left of a
    // segment has winding one more than the face to its right.
    let mut winding: Vec<Option<i32>> = vec![None; cdt.num_all_faces()];
    let mut queue = VecDeque::new();
    for face in cdt.inner_faces() {
        for e in face.adjacent_edges() {
            if e.rev().face().is_outer() {
                let w = net_along(e.from().fix().index(), e.to().fix().index());
                let slot = &mut winding[face.fix().index()];
                match *slot {
                    None => {
                        *slot = Some(w);
                        queue.push_back(face.fix());
                    }
                    Some(old) if old != w => return Err("inconsistent winding at the hull".into()),
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
            let wg = w - net_along(e.from().fix().index(), e.to().fix().index());
            match winding[g.index()] {
                None => {
                    winding[g.index()] = Some(wg);
                    queue.push_back(g);
                }
                Some(old) if old != wg => {
                    return Err(
                        "cut loops are inconsistent (winding differs around a vertex)".into(),
                    );
                }
                Some(_) => {}
            }
        }
    }
    for face in cdt.inner_faces() {
        let w = winding[face.fix().index()].unwrap_or(0);
        if w == 0 {
            continue;
        }
        if w.abs() > 1 {
            return Err(format!(
                "cut loops overlap (winding number {w}): the surface intersects itself"
            ));
        }
        let [a, b, c] = face.vertices().map(|v| owner[v.fix().index()]);
        cap.triangles
            .push(if w < 0 { [a, b, c] } else { [a, c, b] });
    }
    Ok(cap)
}
