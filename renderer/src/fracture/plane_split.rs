//! Splitting a closed mesh by a plane into two closed parts with capped cross-sections.
//!
//! Vertices are classified by the sign of their f64 distance to the plane; a distance of
//! exactly zero puts a vertex *on* the plane, where it is shared by both parts (no snapping
//! tolerance, so nothing moves). Edges whose ends lie strictly on opposite sides get one new
//! vertex, keyed by the undirected edge so both neighbouring triangles use the same one and
//! the cut loops close exactly. Triangles lying in the plane go to the part their normal
//! points away from. The part below is bounded in the plane by the edges it uses only once;
//! those segments are capped by [`super::cap`], and the part above gets the same cap
//! reversed, so the two volumes add up to the original.

use super::cap;
use super::topology::{check_closed_parts, validate};
use super::{FractureError, Fragment};
use crate::mesh::Mesh;
use glam::{DVec3, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// The plane `normal · x = offset`; "below" is `normal · x < offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// Normal, pointing from the part below to the part above (need not be unit length).
    pub normal: DVec3,
    /// Offset along the normal, in units of `normal`'s length.
    pub offset: f64,
}

impl Plane {
    /// The plane `normal · x = offset`.
    #[must_use]
    pub fn new(normal: DVec3, offset: f64) -> Plane {
        Plane { normal, offset }
    }

    /// The plane through `point` with the given normal.
    #[must_use]
    pub fn through(point: DVec3, normal: DVec3) -> Plane {
        Plane {
            normal,
            offset: normal.dot(point),
        }
    }

    /// The same plane with a unit normal, or an error for a zero or non-finite plane.
    fn normalized(&self) -> Result<Plane, FractureError> {
        let len = self.normal.length();
        if !(len.is_finite() && len > 0.0 && self.offset.is_finite()) {
            return Err(FractureError::InvalidPlane {
                normal: self.normal.to_array(),
                offset: self.offset,
            });
        }
        Ok(Plane {
            normal: self.normal / len,
            offset: self.offset / len,
        })
    }
}

/// A side of a plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// `normal · x < offset` (or on the plane).
    Below,
    /// `normal · x > offset` (or on the plane).
    Above,
}

/// Outcome of [`split_mesh`]: a plane that misses the solid is reported as such rather than
/// as an empty part, so callers cannot mistake it for a cut.
#[derive(Clone, Debug, PartialEq)]
pub enum SplitResult {
    /// The plane does not cut the solid; all of it lies on `side` (touching the plane at most).
    Missed {
        /// Where the whole solid lies.
        side: Side,
    },
    /// Both parts, each closed.
    Split {
        /// The part with `normal · x <= offset`.
        below: Fragment,
        /// The part with `normal · x >= offset`.
        above: Fragment,
    },
}

/// Splits a closed mesh by `plane`. `interior` optionally flags input triangles that are
/// already cut faces (they keep the flag); cap faces are flagged in the output.
///
/// # Errors
/// The mesh is invalid or not closed ([`check_closed`](super::check_closed)), `interior` has the wrong
/// length, the plane is degenerate, or the cross-section cannot be capped because the
/// surface intersects itself there.
pub fn split_mesh(
    mesh: &Mesh,
    interior: Option<&[bool]>,
    plane: Plane,
) -> Result<SplitResult, FractureError> {
    split_surface(
        &mesh.positions,
        &mesh.triangles,
        interior,
        &mesh.source,
        plane,
    )
}

/// [`split_mesh`] on loose parts, e.g. a [`Fragment`]'s fields; `source` names the mesh in
/// errors.
///
/// # Errors
/// As [`split_mesh`].
pub fn split_surface(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    interior: Option<&[bool]>,
    source: &Path,
    plane: Plane,
) -> Result<SplitResult, FractureError> {
    let plane = plane.normalized()?;
    check_closed_parts(positions, triangles, source)?;
    check_flags(triangles, interior, source)?;
    Ok(
        match cut(positions, triangles, interior, plane, Keep::Both, source)? {
            Cut::AllBelow => SplitResult::Missed { side: Side::Below },
            Cut::AllAbove => SplitResult::Missed { side: Side::Above },
            Cut::Split { below, above } => {
                let (mut below, mut above) = (below.unwrap_or_default(), above.unwrap_or_default());
                below.separate_sheets();
                above.separate_sheets();
                SplitResult::Split { below, above }
            }
        },
    )
}

impl Fragment {
    /// Splits this fragment like [`split_mesh`]; its interior flags carry over.
    ///
    /// # Errors
    /// As [`split_mesh`], naming `source` (the mesh the fragment came from).
    pub fn split(&self, plane: Plane, source: &Path) -> Result<SplitResult, FractureError> {
        let mut result = split_surface(
            &self.positions,
            &self.triangles,
            Some(&self.interior),
            source,
            plane,
        )?;
        if let SplitResult::Split { below, above } = &mut result {
            below.resolved_crossings += self.resolved_crossings;
            above.resolved_crossings += self.resolved_crossings;
        }
        Ok(result)
    }
}

/// Cuts every piece by `plane` (the pieces a plane misses stay whole): how successive cuts of
/// one object are made. Returns the pieces and whether the plane missed all of them (a cut
/// that cuts nothing is for the caller to report).
///
/// # Errors
/// As [`split_mesh`], naming `source`.
pub fn cut_pieces(
    pieces: Vec<Fragment>,
    plane: Plane,
    source: &Path,
) -> Result<(Vec<Fragment>, bool), FractureError> {
    let mut next = Vec::with_capacity(pieces.len() * 2);
    let mut missed = 0;
    for piece in pieces {
        match piece.split(plane, source)? {
            SplitResult::Missed { .. } => {
                missed += 1;
                next.push(piece);
            }
            SplitResult::Split { below, above } => next.extend([below, above]),
        }
    }
    let all_missed = missed == next.len();
    Ok((next, all_missed))
}

pub(crate) fn check_flags(
    triangles: &[[u32; 3]],
    interior: Option<&[bool]>,
    source: &Path,
) -> Result<(), FractureError> {
    match interior {
        Some(flags) if flags.len() != triangles.len() => Err(FractureError::FlagCount {
            mesh: source.to_path_buf(),
            flags: flags.len(),
            triangles: triangles.len(),
        }),
        _ => Ok(()),
    }
}

/// Which parts [`cut`] builds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Keep {
    Both,
    Below,
}

/// Result of [`cut`].
pub(crate) enum Cut {
    AllBelow,
    AllAbove,
    Split {
        below: Option<Fragment>,
        above: Option<Fragment>,
    },
}

/// The cutting core. The input must be valid and closed (not checked here, so repeated
/// Voronoi clips do not pay for it); `plane` must have a unit normal.
pub(crate) fn cut(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    interior: Option<&[bool]>,
    plane: Plane,
    keep: Keep,
    source: &Path,
) -> Result<Cut, FractureError> {
    validate(positions, triangles, source)?;
    let n = plane.normal;
    let dist: Vec<f64> = positions
        .iter()
        .map(|p| n.dot(p.as_dvec3()) - plane.offset)
        .collect();
    let side: Vec<i8> = dist
        .iter()
        .map(|&s| {
            if s > 0.0 {
                1
            } else if s < 0.0 {
                -1
            } else {
                0
            }
        })
        .collect();
    let (mut any_below, mut any_above) = (false, false);
    for &i in triangles.iter().flatten() {
        any_below |= side[i as usize] < 0;
        any_above |= side[i as usize] > 0;
    }
    if !any_above {
        return Ok(Cut::AllBelow);
    }
    if !any_below {
        return Ok(Cut::AllAbove);
    }

    let base = positions.len() as u32;
    let mut cut_exact: Vec<DVec3> = Vec::new(); // new vertices, f64 (for the cap)
    let mut cut_key: HashMap<(u32, u32), u32> = HashMap::new();
    // The new vertex on edge (a, b), computed from the lower index so it is the same point
    // whichever triangle asks first.
    let cut_vertex = |a: u32,
                      b: u32,
                      cut_exact: &mut Vec<DVec3>,
                      cut_key: &mut HashMap<(u32, u32), u32>|
     -> u32 {
        let key = if a < b { (a, b) } else { (b, a) };
        *cut_key.entry(key).or_insert_with(|| {
            let (pa, pb) = (
                positions[key.0 as usize].as_dvec3(),
                positions[key.1 as usize].as_dvec3(),
            );
            let (sa, sb) = (dist[key.0 as usize], dist[key.1 as usize]);
            let t = sa / (sa - sb);
            cut_exact.push(pa + (pb - pa) * t);
            base + cut_exact.len() as u32 - 1
        })
    };

    let mut below = Part::default();
    let mut above = Part::default();
    let mut plane_edges: Vec<(u64, i32)> = Vec::new(); // in-plane edges of the part below
    let on_plane = |id: u32, side: &[i8]| id >= base || side[id as usize] == 0;

    for (t, tri) in triangles.iter().enumerate() {
        let flag = interior.is_some_and(|f| f[t]);
        let s = tri.map(|i| side[i as usize]);
        let has_neg = s.contains(&-1);
        let has_pos = s.contains(&1);
        let goes_below = if !has_neg && !has_pos {
            // Lies in the plane: it belongs to the part its outward normal leaves from.
            let [a, b, c] = tri.map(|i| positions[i as usize].as_dvec3());
            (b - a).cross(c - a).dot(n) >= 0.0
        } else {
            !has_pos
        };
        if !has_neg || !has_pos {
            if goes_below {
                below.push(*tri, flag);
            } else if keep == Keep::Both {
                above.push(*tri, flag);
            }
            continue;
        }
        // Crossing triangle: clip it into a polygon on each side.
        let mut poly_below: Vec<u32> = Vec::with_capacity(4);
        let mut poly_above: Vec<u32> = Vec::with_capacity(4);
        for k in 0..3 {
            let (p, q) = (tri[k], tri[(k + 1) % 3]);
            let (sp, sq) = (s[k], s[(k + 1) % 3]);
            if sp <= 0 {
                poly_below.push(p);
            }
            if sp >= 0 {
                poly_above.push(p);
            }
            if sp * sq < 0 {
                let c = cut_vertex(p, q, &mut cut_exact, &mut cut_key);
                poly_below.push(c);
                poly_above.push(c);
            }
        }
        below.push_polygon(&poly_below, flag, positions, &cut_exact, base);
        if keep == Keep::Both {
            above.push_polygon(&poly_above, flag, positions, &cut_exact, base);
        }
    }
    // Edges of the part below lying in the plane; those used once (net) bound the cap.
    for tri in &below.triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if on_plane(a, &side) && on_plane(b, &side) {
                let (lo, hi, sign) = if a < b { (a, b, 1) } else { (b, a, -1) };
                plane_edges.push(((u64::from(lo) << 32) | u64::from(hi), sign));
            }
        }
    }
    plane_edges.sort_unstable();
    let mut segments: Vec<(u32, u32)> = Vec::new();
    let mut i = 0;
    while i < plane_edges.len() {
        let key = plane_edges[i].0;
        let mut sum = 0;
        while i < plane_edges.len() && plane_edges[i].0 == key {
            sum += plane_edges[i].1;
            i += 1;
        }
        let (lo, hi) = ((key >> 32) as u32, key as u32);
        for _ in 0..sum.unsigned_abs() {
            segments.push(if sum > 0 { (lo, hi) } else { (hi, lo) });
        }
    }

    // 2D frame (e1, e2, n) right-handed, so counter-clockwise in 2D faces along +n.
    let helper = if n.x.abs() <= n.y.abs() && n.x.abs() <= n.z.abs() {
        DVec3::X
    } else if n.y.abs() <= n.z.abs() {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let e1 = n.cross(helper).normalize();
    let e2 = n.cross(e1);
    let exact = |id: u32| {
        if id < base {
            positions[id as usize].as_dvec3()
        } else {
            cut_exact[(id - base) as usize]
        }
    };
    let origin = segments
        .first()
        .map(|&(u, _)| exact(u))
        .unwrap_or(DVec3::ZERO);
    let first_new = base + cut_exact.len() as u32;
    let cap = cap::triangulate(
        &segments,
        |id| {
            let d = exact(id) - origin;
            [d.dot(e1), d.dot(e2)]
        },
        first_new,
    )
    .map_err(|reason| FractureError::Cap {
        mesh: source.to_path_buf(),
        reason,
    })?;
    // Vertices the cap added (where crossing segments were split, and interior points), in
    // id order, each on the line between two earlier vertices.
    for v in &cap.new_vertices {
        debug_assert_eq!(v.id, base + cut_exact.len() as u32);
        let at = |id: u32| {
            if id < base {
                positions[id as usize].as_dvec3()
            } else {
                cut_exact[(id - base) as usize]
            }
        };
        let p = at(v.from) + (at(v.to) - at(v.from)) * v.t;
        cut_exact.push(p);
    }

    let new_positions: Vec<Vec3> = cut_exact.iter().map(|p| p.as_vec3()).collect();
    let vertex = |id: u32| {
        if id < base {
            positions[id as usize]
        } else {
            new_positions[(id - base) as usize]
        }
    };
    let below_splits: HashMap<(u32, u32), Vec<u32>> = cap.splits.iter().cloned().collect();
    let welds: HashMap<u32, u32> = cap.welds.iter().copied().collect();
    below.split_edges(&below_splits);
    below.weld(&welds);
    for tri in &cap.triangles {
        below.push(*tri, true);
    }
    let below = Some(below.compact(vertex, cap.crossings));
    let above = if keep == Keep::Both {
        let above_splits: HashMap<(u32, u32), Vec<u32>> = cap
            .splits
            .iter()
            .map(|((u, v), chain)| ((*v, *u), chain.iter().rev().copied().collect()))
            .collect();
        above.split_edges(&above_splits);
        above.weld(&welds);
        for &[a, b, c] in &cap.triangles {
            above.push([a, c, b], true);
        }
        Some(above.compact(vertex, cap.crossings))
    } else {
        None
    };
    Ok(Cut::Split { below, above })
}

/// One side's triangles in the shared id space (input vertices, then new cut vertices).
#[derive(Default)]
struct Part {
    triangles: Vec<[u32; 3]>,
    interior: Vec<bool>,
}

impl Part {
    fn push(&mut self, tri: [u32; 3], flag: bool) {
        self.triangles.push(tri);
        self.interior.push(flag);
    }

    /// Adds a clipped triangle (3 or 4 corners, convex); a quad is split along its shorter
    /// diagonal to avoid needless slivers.
    fn push_polygon(
        &mut self,
        poly: &[u32],
        flag: bool,
        positions: &[Vec3],
        cut: &[DVec3],
        base: u32,
    ) {
        match *poly {
            [a, b, c] => self.push([a, b, c], flag),
            [a, b, c, d] => {
                let at = |id: u32| {
                    if id < base {
                        positions[id as usize].as_dvec3()
                    } else {
                        cut[(id - base) as usize]
                    }
                };
                if at(a).distance_squared(at(c)) <= at(b).distance_squared(at(d)) {
                    self.push([a, b, c], flag);
                    self.push([a, c, d], flag);
                } else {
                    self.push([a, b, d], flag);
                    self.push([b, c, d], flag);
                }
            }
            _ => {}
        }
    }

    /// Inserts the vertices that the cap put on directed edges (`(u, v)` -> vertices from `u`
    /// to `v`) into the triangles using those edges, so no T-junction remains.
    fn split_edges(&mut self, splits: &HashMap<(u32, u32), Vec<u32>>) {
        if splits.is_empty() {
            return;
        }
        let mut out = Part::default();
        for (tri, &flag) in self.triangles.iter().zip(&self.interior) {
            let mut poly = Vec::with_capacity(4);
            let mut apex = None;
            let mut longest = 0;
            for k in 0..3 {
                poly.push(tri[k]);
                if let Some(chain) = splits.get(&(tri[k], tri[(k + 1) % 3])) {
                    if chain.len() > longest {
                        longest = chain.len();
                        apex = Some(tri[(k + 2) % 3]);
                    }
                    poly.extend_from_slice(chain);
                }
            }
            let Some(apex) = apex else {
                out.push(*tri, flag);
                continue;
            };
            let start = poly.iter().position(|&v| v == apex).unwrap_or(0);
            let m = poly.len();
            for i in 1..m - 1 {
                out.push(
                    [apex, poly[(start + i) % m], poly[(start + i + 1) % m]],
                    flag,
                );
            }
        }
        *self = out;
    }

    /// Replaces welded vertex ids and drops the triangles that collapse.
    fn weld(&mut self, welds: &HashMap<u32, u32>) {
        if welds.is_empty() {
            return;
        }
        let mut out = Part::default();
        for (tri, &flag) in self.triangles.iter().zip(&self.interior) {
            let t = tri.map(|i| welds.get(&i).copied().unwrap_or(i));
            if t[0] != t[1] && t[1] != t[2] && t[2] != t[0] {
                out.push(t, flag);
            }
        }
        *self = out;
    }

    /// Renumbers the used vertices in order of first use.
    fn compact(self, vertex: impl Fn(u32) -> Vec3, resolved_crossings: usize) -> Fragment {
        let mut map: HashMap<u32, u32> = HashMap::new();
        let mut positions = Vec::new();
        let triangles = self
            .triangles
            .iter()
            .map(|tri| {
                tri.map(|id| {
                    *map.entry(id).or_insert_with(|| {
                        positions.push(vertex(id));
                        positions.len() as u32 - 1
                    })
                })
            })
            .collect();
        Fragment {
            positions,
            triangles,
            interior: self.interior,
            resolved_crossings,
            separated_vertices: 0,
            split_edges: 0,
        }
    }
}
