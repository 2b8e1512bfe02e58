//! Cutting closed meshes into closed pieces: plane splits and Voronoi fracture, with the new
//! (cap) faces marked so that the synthesizer requests their voxels and other tools can give
//! them their own material.
//!
//! Every piece is a closed, consistently oriented surface whose volume is the volume of the
//! solid it holds: cut vertices are shared through the edge they lie on, so the cut loops close
//! exactly, and each cross-section is triangulated once (a constrained Delaunay triangulation,
//! `spade`) and used by both sides, reversed. Pieces stay in the coordinates of the mesh they
//! came from, which is what keeps a solid texture continuous across a crack. Design, limits
//! and measurements: `docs/fracture.md`.

mod cap;
mod error;
mod manifold;
mod obj_write;
mod plane_split;
mod topology;
mod voronoi;

pub use error::FractureError;
pub use obj_write::{write_fragment_obj, write_material_library};
pub use plane_split::{cut_pieces, split_mesh, split_surface, Plane, Side, SplitResult};
pub use topology::{check_closed, check_closed_parts, edge_report, volume, EdgeReport};
pub use voronoi::{fracture, fracture_cells, fracture_cells_flagged, random_sites, MAX_PIECES};

use crate::mesh::Mesh;
use glam::{DVec3, Vec3};
use std::path::PathBuf;

/// One closed piece of a cut or fractured mesh.
///
/// Kept apart from [`Mesh`] because a piece has no file of its own but must remember which
/// faces are new (cut) surface: the renderer requests their voxels from lazy synthesis, and a
/// later cut keeps the flags.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Fragment {
    /// Vertex positions (only the vertices the triangles use), in the coordinates of the mesh
    /// it came from.
    pub positions: Vec<Vec3>,
    /// Triangles, counter-clockwise seen from outside, like [`Mesh::triangles`].
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: `true` for cap faces made by a cut (here or in an earlier cut).
    pub interior: Vec<bool>,
    /// Crossings of cut segments resolved in the caps that made this piece (here and in
    /// earlier cuts): non-zero only where the input surface intersects itself, which scans
    /// often do. Reported so a user knows the pieces inherit that self-intersection.
    pub resolved_crossings: usize,
    /// Vertex copies made so that the piece is a 2-manifold: where sheets of a
    /// self-intersecting input met at an edge used by four triangles or at a vertex, each
    /// sheet got its own copy of the vertex (at the same position). Zero on surfaces without
    /// self-intersections.
    pub separated_vertices: usize,
    /// Edges split at their midpoint because two sheets still shared both their ends after
    /// the vertex copies (each split also adds one vertex).
    pub split_edges: usize,
}

impl Fragment {
    /// The whole mesh as one piece (no cap faces yet): where successive cuts start.
    #[must_use]
    pub fn whole(mesh: &Mesh) -> Fragment {
        Fragment {
            positions: mesh.positions.clone(),
            triangles: mesh.triangles.clone(),
            interior: vec![false; mesh.triangles.len()],
            resolved_crossings: 0,
            separated_vertices: 0,
            split_edges: 0,
        }
    }

    /// Separates the sheets that meet at an edge or vertex of this piece (see
    /// [`separated_vertices`](Self::separated_vertices)), replacing the counts with this
    /// separation's.
    fn separate_sheets(&mut self) {
        let s = manifold::separate_sheets(self);
        self.separated_vertices = s.vertices;
        self.split_edges = s.edges;
    }

    /// Signed volume in f64 (positive for an outward-oriented closed piece); see [`volume`].
    #[must_use]
    pub fn volume(&self) -> f64 {
        volume(&self.positions, &self.triangles)
    }

    /// Centre of mass of the solid piece (uniform density): where an explosion pushes it from
    /// and what it spins about.
    #[must_use]
    pub fn centroid(&self) -> Vec3 {
        let Some(origin) = self.positions.first().map(|p| p.as_dvec3()) else {
            return Vec3::ZERO;
        };
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.positions[i as usize].as_dvec3() - origin);
            let w = a.dot(b.cross(c));
            sum += (a + b + c) * w;
            weight += w;
        }
        if weight == 0.0 {
            return origin.as_vec3();
        }
        (origin + sum / (4.0 * weight)).as_vec3()
    }

    /// The triangles of one kind: the cap faces (`interior`) or the original surface.
    pub fn triangles_of(&self, interior: bool) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.triangles
            .iter()
            .zip(&self.interior)
            .filter(move |(_, &f)| f == interior)
            .map(|(t, _)| *t)
    }

    /// The piece as a [`Mesh`] (dropping the interior flags) named `source`, for code that
    /// takes meshes.
    #[must_use]
    pub fn to_mesh(&self, source: PathBuf) -> Mesh {
        Mesh {
            positions: self.positions.clone(),
            triangles: self.triangles.clone(),
            uvs: None,
            source,
        }
    }
}
