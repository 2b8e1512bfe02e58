//! Tangent frames of meshes with texture coordinates: MikkTSpace (through `bevy_mikktspace`),
//! the convention normal-map bakers write tangent-space maps in, so a map made for a mesh by
//! another tool reads back the same way here.

use crate::mesh::Mesh;
use glam::{Vec2, Vec3, Vec4};

/// The unit tangent (xyz) of every triangle corner and the bitangent's sign (w): the bitangent
/// is `w · (n × t)` for the corner's shading normal n, as MikkTSpace defines it. `None` when
/// the mesh has no texture coordinates. Corners whose coordinates give no direction (a
/// triangle collapsed in UV) get a tangent perpendicular to the normal and w = 1.
pub fn corner_tangents(mesh: &Mesh, normals: &[[Vec3; 3]]) -> Option<Vec<[Vec4; 3]>> {
    let uvs = mesh.uvs.as_ref()?;
    let mut geometry = Corners {
        mesh,
        uvs,
        normals,
        tangents: vec![[Vec4::ZERO; 3]; mesh.triangles.len()],
    };
    let ok = bevy_mikktspace::generate_tangents(&mut geometry);
    let mut tangents = geometry.tangents;
    for (t, n) in tangents.iter_mut().zip(normals) {
        for k in 0..3 {
            let v = t[k].truncate();
            let v = (v - n[k] * n[k].dot(v)).normalize_or_zero();
            t[k] = if ok && v != Vec3::ZERO {
                v.extend(if t[k].w < 0.0 { -1.0 } else { 1.0 })
            } else {
                n[k].any_orthonormal_vector().extend(1.0)
            };
        }
    }
    Some(tangents)
}

struct Corners<'a> {
    mesh: &'a Mesh,
    uvs: &'a [Vec2],
    normals: &'a [[Vec3; 3]],
    tangents: Vec<[Vec4; 3]>,
}

impl bevy_mikktspace::Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.triangles.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.mesh.triangles[face][vert] as usize].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.normals[face][vert].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.uvs[self.mesh.triangles[face][vert] as usize].to_array()
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        self.tangents[face][vert] = Vec4::from_array(tangent);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::corner_normals;

    #[test]
    fn the_unit_quad_has_u_along_x_and_v_along_minus_z() {
        let quad = Mesh::unit_quad();
        let normals = corner_normals(&quad, 50.0);
        let tangents = corner_tangents(&quad, &normals).expect("the quad has UVs");
        for (t, n) in tangents.iter().zip(&normals) {
            for k in 0..3 {
                assert!((t[k].truncate() - Vec3::X).length() < 1e-5, "{t:?}");
                assert!((n[k] - Vec3::Y).length() < 1e-5);
                // Bitangent w (n × t) = +y × +x = −z: the direction v grows in.
                assert_eq!(t[k].w, 1.0);
                assert!((n[k].cross(t[k].truncate()) * t[k].w - Vec3::NEG_Z).length() < 1e-5);
            }
        }
    }

    #[test]
    fn a_mirrored_uv_layout_flips_the_bitangent_sign() {
        let mut quad = Mesh::unit_quad();
        for uv in quad.uvs.as_mut().unwrap() {
            uv.x = 1.0 - uv.x;
        }
        let normals = corner_normals(&quad, 50.0);
        let tangents = corner_tangents(&quad, &normals).unwrap();
        for t in tangents.iter().flatten() {
            assert!((t.truncate() - Vec3::NEG_X).length() < 1e-5, "{t:?}");
            assert_eq!(t.w, -1.0);
        }
    }

    #[test]
    fn meshes_without_uvs_have_no_tangents() {
        let cube = Mesh::unit_cube();
        assert!(corner_tangents(&cube, &corner_normals(&cube, 50.0)).is_none());
    }
}
