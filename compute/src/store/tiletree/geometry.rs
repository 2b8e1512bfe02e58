//! The surface in grid units (unit cube × R, exact since R is a power of two), the six faces
//! a triangle may be projected onto, and the column–triangle intersection that both the fold
//! test and the texel fill use. `glsl/include/store/tiletree_build.glsl` repeats
//! [`column_hit`] operation for operation (every value `precise`), so GPU and CPU agree bit
//! for bit.

use super::NAME;
use crate::store::StoreError;
use glam::Vec3;

/// A triangle belongs to the *cone* of face (axis a, sign s) when s·n_a ≥ CONE·|n|: wider than
/// the region where the face is the normal's dominant one (|n_a| ≥ 1/√3 ≈ 0.577), so the
/// texels around a point where the lookup switches faces are filled from real surface on both
/// sides of the switch.
pub const CONE: f32 = 0.4;
/// Voxels beyond the leaf's slab (along the face axis) in which a texel still takes a surface
/// hit: a cone surface moves at most √(1 − 0.4²)/0.4 ≈ 2.3 voxels in depth per texel.
pub const MARGIN: f32 = 3.0;
/// Two hits of one column inside a leaf closer than this (voxels) are one sheet, not a fold:
/// they fall into the same or neighbouring voxels, whose colours a tile cannot tell apart.
pub const FOLD_TOLERANCE: f32 = 1.0;

/// A face's tile covers, besides the triangles a lookup with their geometric normal reads
/// through it, those whose score s·n_a on it is within this fraction of |n| of their best
/// kept face's: a normal tilted from the geometric one (a smooth normal, a rounding of the hit
/// point) can pick that face, and its tile must then still hold the point.
pub const SWITCH_MARGIN: f32 = 0.2;

/// Face index 2·axis + (sign < 0): +X, −X, +Y, −Y, +Z, −Z.
pub fn face_axis(face: u32) -> (usize, f32) {
    ((face / 2) as usize, if face & 1 == 0 { 1.0 } else { -1.0 })
}

/// The in-plane axes (b, c) of a face whose normal axis is `a`.
pub fn plane_axes(a: usize) -> (usize, usize) {
    ((a + 1) % 3, (a + 2) % 3)
}

/// The face a normal selects: its dominant axis (ties to the lower axis) and sign (≥ 0: +).
pub fn dominant_face(n: Vec3) -> u32 {
    let an = n.abs();
    let mut a = 0;
    if an.y > an[a] {
        a = 1;
    }
    if an.z > an[a] {
        a = 2;
    }
    2 * a as u32 + (n[a] < 0.0) as u32
}

/// The mesh in grid units with, per triangle, its dominant face and its cone mask.
pub struct Surface {
    /// Vertex positions × R.
    pub positions: Vec<Vec3>,
    /// Triangles (vertex indices).
    pub triangles: Vec<[u32; 3]>,
    /// Dominant face of each triangle, or `u32::MAX` for a degenerate (zero-area) triangle,
    /// which is ignored.
    pub face: Vec<u32>,
    /// Bit f set when the triangle lies in the cone of face f.
    pub cones: Vec<u8>,
}

impl Surface {
    /// Checks and scales a mesh of the unit cube to grid units.
    ///
    /// # Errors
    /// No triangle, a vertex index out of range, a non-finite coordinate, a vertex outside
    /// [0, 1]³ (the mesh must be normalized first), or only degenerate triangles.
    pub fn new(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        resolution: u32,
    ) -> Result<Surface, StoreError> {
        let bad = |problem: String| StoreError::Config {
            store: NAME,
            problem,
        };
        if triangles.is_empty() {
            return Err(bad("the mesh has no triangle".into()));
        }
        if let Some((i, p)) = positions
            .iter()
            .enumerate()
            .find(|(_, p)| !p.is_finite() || p.min_element() < 0.0 || p.max_element() > 1.0)
        {
            return Err(bad(format!(
                "vertex {i} at {p} is not finite or lies outside the unit cube [0, 1]³ (normalize the mesh first)"
            )));
        }
        crate::voxel::check_triangles(positions, triangles)
            .map_err(|e| bad(format!("malformed mesh: {e}")))?;
        let r = resolution as f32;
        let positions: Vec<Vec3> = positions.iter().map(|&p| p * r).collect();
        let mut face = Vec::with_capacity(triangles.len());
        let mut cones = Vec::with_capacity(triangles.len());
        for t in triangles {
            let [p0, p1, p2] = t.map(|i| positions[i as usize]);
            let n = (p1 - p0).cross(p2 - p0);
            let len2 = n.length_squared();
            if len2 == 0.0 || !len2.is_finite() {
                face.push(u32::MAX);
                cones.push(0);
                continue;
            }
            face.push(dominant_face(n));
            let mut mask = 0u8;
            for f in 0..6 {
                let (a, s) = face_axis(f);
                if s * n[a] > 0.0 && n[a] * n[a] >= CONE * CONE * len2 {
                    mask |= 1 << f;
                }
            }
            cones.push(mask);
        }
        if face.iter().all(|&f| f == u32::MAX) {
            return Err(bad(format!(
                "all {} triangles are degenerate (zero area)",
                triangles.len()
            )));
        }
        Ok(Surface {
            positions,
            triangles: triangles.to_vec(),
            face,
            cones,
        })
    }

    /// The three vertices of triangle `t` in grid units.
    pub fn vertices(&self, t: u32) -> [Vec3; 3] {
        self.triangles[t as usize].map(|i| self.positions[i as usize])
    }
}

/// Where the line along axis `a` through the column centre (`cu`, `cv`) (coordinates along the
/// in-plane axes b, c in grid units) meets the triangle `v`: its coordinate along `a`, or
/// `None` when the column misses the triangle or the triangle is edge-on. Edges count as hits.
pub fn column_hit(v: [Vec3; 3], a: usize, cu: f32, cv: f32) -> Option<f32> {
    let (b, c) = plane_axes(a);
    let edge = |p: Vec3, q: Vec3| (q[b] - p[b]) * (cv - p[c]) - (q[c] - p[c]) * (cu - p[b]);
    let e0 = edge(v[1], v[2]);
    let e1 = edge(v[2], v[0]);
    let e2 = edge(v[0], v[1]);
    let area = e0 + e1 + e2;
    if area == 0.0 {
        return None;
    }
    let inside = (e0 >= 0.0 && e1 >= 0.0 && e2 >= 0.0) || (e0 <= 0.0 && e1 <= 0.0 && e2 <= 0.0);
    if !inside {
        return None;
    }
    Some((e0 * v[0][a] + e1 * v[1][a] + e2 * v[2][a]) / area)
}
