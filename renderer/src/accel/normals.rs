//! Shading normals: area-weighted vertex normals that do not smooth across creases, so a cube
//! stays a cube and a scanned mesh looks smooth.

use crate::mesh::Mesh;
use glam::Vec3;

/// Unit normal of every triangle corner: the area-weighted average of the normals of the
/// triangles sharing that vertex whose normal is within `crease_deg` of this triangle's.
/// Degenerate triangles get their neighbours' normal or +z.
pub fn corner_normals(mesh: &Mesh, crease_deg: f32) -> Vec<[Vec3; 3]> {
    let p = &mesh.positions;
    // Face normals scaled by twice the area.
    let face: Vec<Vec3> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| p[i as usize]);
            (b - a).cross(c - a)
        })
        .collect();
    let mut incident: Vec<Vec<u32>> = vec![Vec::new(); p.len()];
    for (f, t) in mesh.triangles.iter().enumerate() {
        for &v in t {
            incident[v as usize].push(f as u32);
        }
    }
    let cos_crease = crease_deg.to_radians().cos();
    mesh.triangles
        .iter()
        .enumerate()
        .map(|(f, t)| {
            let nf = face[f].normalize_or_zero();
            t.map(|v| {
                let sum: Vec3 = incident[v as usize]
                    .iter()
                    .map(|&g| face[g as usize])
                    .filter(|n| nf == Vec3::ZERO || n.normalize_or_zero().dot(nf) >= cos_crease)
                    .sum();
                let n = sum.normalize_or_zero();
                if n != Vec3::ZERO {
                    n
                } else if nf != Vec3::ZERO {
                    nf
                } else {
                    Vec3::Z
                }
            })
        })
        .collect()
}

/// Octahedral encoding of a unit vector in 2×16 bits (snorm), the layout `decode_octahedral`
/// in `glsl/include/render/cwbvh.glsl` reads.
pub fn encode_octahedral(n: Vec3) -> u32 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    let mut x = n.x / l1;
    let mut y = n.y / l1;
    if n.z < 0.0 {
        let (ox, oy) = (x, y);
        x = (1.0 - oy.abs()) * sign(ox);
        y = (1.0 - ox.abs()) * sign(oy);
    }
    let q = |v: f32| ((v.clamp(-1.0, 1.0) * 32767.0).round() as i32 as u32) & 0xffff;
    q(x) | (q(y) << 16)
}

fn sign(v: f32) -> f32 {
    if v >= 0.0 {
        1.0
    } else {
        -1.0
    }
}
