//! Closedness checks and volume: a cut only makes sense on a surface that bounds a solid, and
//! the volume is how tests (and callers) verify that fragments add up to the original.

use super::FractureError;
use crate::mesh::Mesh;
use glam::{DVec3, Vec3};
use std::path::Path;

/// Counts of offending edges of a triangle soup, see [`edge_report`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EdgeReport {
    /// Undirected edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Undirected edges used by two or more triangles but more often in one direction than
    /// the other (inconsistent orientation, or a sheet ending at the edge).
    pub non_manifold_edges: usize,
    /// Undirected edges used by four or more triangles, as often in each direction: where two
    /// sheets of a self-intersecting surface meet (fracture of such a surface makes them where
    /// its caps lie over each other). They leave the surface closed.
    pub shared_edges: usize,
}

impl EdgeReport {
    /// `true` when every edge is used as often in each direction (a closed, consistently
    /// oriented surface, which bounds a solid with a well-defined winding number). On a
    /// surface without [`shared_edges`](Self::shared_edges) that is a closed 2-manifold.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.boundary_edges == 0 && self.non_manifold_edges == 0
    }
}

/// Checks the basics every later step indexes on: at least one triangle, indices in range, no
/// triangle using a vertex twice, finite coordinates.
///
/// # Errors
/// [`FractureError::Empty`], [`FractureError::IndexOutOfRange`],
/// [`FractureError::RepeatedIndex`] or [`FractureError::NonFinite`], naming `source`.
pub fn validate(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    source: &Path,
) -> Result<(), FractureError> {
    if triangles.is_empty() {
        return Err(FractureError::Empty {
            mesh: source.to_path_buf(),
        });
    }
    for (t, tri) in triangles.iter().enumerate() {
        for &i in tri {
            if i as usize >= positions.len() {
                return Err(FractureError::IndexOutOfRange {
                    mesh: source.to_path_buf(),
                    triangle: t,
                    index: i,
                    vertex_count: positions.len(),
                });
            }
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
            return Err(FractureError::RepeatedIndex {
                mesh: source.to_path_buf(),
                triangle: t,
            });
        }
    }
    if let Some(vertex) = positions.iter().position(|p| !p.is_finite()) {
        return Err(FractureError::NonFinite {
            mesh: source.to_path_buf(),
            vertex,
        });
    }
    Ok(())
}

/// Counts boundary and non-manifold edges by sorting the directed edges (deterministic and
/// without hashing). Indices must be in range; triangles that repeat an index contribute their
/// degenerate edges like any other.
#[must_use]
pub fn edge_report(triangles: &[[u32; 3]]) -> EdgeReport {
    // Key: undirected edge (min << 32 | max); flag: whether the triangle runs min -> max.
    let mut edges: Vec<(u64, bool)> = Vec::with_capacity(triangles.len() * 3);
    for tri in triangles {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            edges.push(((u64::from(lo) << 32) | u64::from(hi), a < b));
        }
    }
    edges.sort_unstable();
    let mut report = EdgeReport::default();
    let mut start = 0;
    while start < edges.len() {
        let key = edges[start].0;
        let mut end = start;
        let mut forward = 0usize;
        while end < edges.len() && edges[end].0 == key {
            forward += usize::from(edges[end].1);
            end += 1;
        }
        let uses = end - start;
        match uses {
            1 => report.boundary_edges += 1,
            _ if 2 * forward != uses => report.non_manifold_edges += 1,
            2 => {}
            _ => report.shared_edges += 1,
        }
        start = end;
    }
    report
}

/// Checks that `mesh` is valid (`validate`) and closed and consistently oriented (every edge
/// used as often in each direction), which is what splitting needs: only then do the cut
/// segments form closed loops and the two parts bound solids.
///
/// # Errors
/// The errors of `validate`, or [`FractureError::NotClosed`] with the counts of boundary and
/// non-manifold edges.
pub fn check_closed(mesh: &Mesh) -> Result<(), FractureError> {
    check_closed_parts(&mesh.positions, &mesh.triangles, &mesh.source)
}

/// [`check_closed`] on loose parts, for fragments (which have no source path of their own).
///
/// # Errors
/// As [`check_closed`].
pub fn check_closed_parts(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    source: &Path,
) -> Result<(), FractureError> {
    validate(positions, triangles, source)?;
    let report = edge_report(triangles);
    if report.is_closed() {
        Ok(())
    } else {
        Err(FractureError::NotClosed {
            mesh: source.to_path_buf(),
            boundary_edges: report.boundary_edges,
            non_manifold_edges: report.non_manifold_edges,
        })
    }
}

/// Signed volume enclosed by the triangles (divergence theorem), positive for a closed mesh
/// oriented counter-clockwise from outside. Summed in f64 relative to the first vertex, so
/// meshes far from the origin keep their precision. Out-of-range indices are skipped.
#[must_use]
pub fn volume(positions: &[Vec3], triangles: &[[u32; 3]]) -> f64 {
    let Some(origin) = positions.first().map(|p| p.as_dvec3()) else {
        return 0.0;
    };
    let at = |i: u32| positions.get(i as usize).map(|p| p.as_dvec3() - origin);
    let mut sum = 0.0;
    for tri in triangles {
        if let (Some(a), Some(b), Some(c)) = (at(tri[0]), at(tri[1]), at(tri[2])) {
            sum += a.dot(b.cross(c));
        }
    }
    sum / 6.0
}

/// Axis-aligned bounds of the vertices that `triangles` use, in f64.
pub(crate) fn used_bounds(positions: &[Vec3], triangles: &[[u32; 3]]) -> Option<(DVec3, DVec3)> {
    let mut iter = triangles
        .iter()
        .flatten()
        .map(|&i| positions[i as usize].as_dvec3());
    let first = iter.next()?;
    Some(iter.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}
