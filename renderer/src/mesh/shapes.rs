//! Built-in generated meshes for scenes that need a floor, a box or a ball without a file.
//! They live in the same unit cube [0, 1]^3 as normalized meshes, so that solid textures and
//! instance transforms treat them exactly like loaded ones, and they are closed and outward
//! oriented (counter-clockwise seen from outside) where they enclose a volume.

use super::Mesh;
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::PathBuf;

/// Most subdivisions [`Mesh::icosphere`] accepts: 7 gives 327 680 triangles, beyond which a
/// tessellated sphere only costs memory.
pub const MAX_ICOSPHERE_SUBDIVISIONS: u32 = 7;

fn generated(name: &str, positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Mesh {
    Mesh {
        positions,
        triangles,
        uvs: None,
        source: PathBuf::from(format!("<{name}>")),
    }
}

impl Mesh {
    /// The square [0, 1] × {0} × [0, 1] in the xz-plane, facing +y: a floor, a wall or a
    /// ceiling once placed (two triangles). Its texture coordinates are (x, 1 − z): seen from
    /// above with −z ahead, an image lies the right way up (its top row at z = 0).
    pub fn unit_quad() -> Mesh {
        let positions = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        let uvs = positions
            .iter()
            .map(|p| Vec2::new(p.x, 1.0 - p.z))
            .collect();
        Mesh {
            uvs: Some(uvs),
            ..generated("quad", positions, vec![[0, 2, 1], [0, 3, 2]])
        }
    }

    /// The cube [0, 1]^3: 8 shared corners, 12 outward triangles.
    pub fn unit_cube() -> Mesh {
        // Corner i has coordinates (i & 1, (i >> 1) & 1, (i >> 2) & 1).
        let positions = (0..8u32)
            .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
            .collect();
        // Each face as a quad a, b, c, d counter-clockwise seen from outside.
        let faces: [[u32; 4]; 6] = [
            [0, 4, 6, 2], // x = 0
            [1, 3, 7, 5], // x = 1
            [0, 1, 5, 4], // y = 0
            [2, 6, 7, 3], // y = 1
            [0, 2, 3, 1], // z = 0
            [4, 5, 7, 6], // z = 1
        ];
        let triangles = faces
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        generated("cube", positions, triangles)
    }

    /// The sphere of centre (0.5, 0.5, 0.5) and radius 0.5 as a subdivided icosahedron:
    /// 10·4^s + 2 vertices and 20·4^s triangles of nearly equal size, outward oriented.
    ///
    /// # Panics
    /// If `subdivisions` exceeds [`MAX_ICOSPHERE_SUBDIVISIONS`] (scene loading checks it).
    pub fn icosphere(subdivisions: u32) -> Mesh {
        assert!(
            subdivisions <= MAX_ICOSPHERE_SUBDIVISIONS,
            "icosphere subdivisions {subdivisions} exceed {MAX_ICOSPHERE_SUBDIVISIONS}"
        );
        let t = (1.0 + 5f32.sqrt()) / 2.0;
        let mut unit: Vec<Vec3> = [
            (-1.0, t, 0.0),
            (1.0, t, 0.0),
            (-1.0, -t, 0.0),
            (1.0, -t, 0.0),
            (0.0, -1.0, t),
            (0.0, 1.0, t),
            (0.0, -1.0, -t),
            (0.0, 1.0, -t),
            (t, 0.0, -1.0),
            (t, 0.0, 1.0),
            (-t, 0.0, -1.0),
            (-t, 0.0, 1.0),
        ]
        .iter()
        .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
        .collect();
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            triangles = subdivide(&mut unit, &triangles);
        }
        let positions = unit.iter().map(|&p| p * 0.5 + Vec3::splat(0.5)).collect();
        generated(&format!("icosphere {subdivisions}"), positions, triangles)
    }
}

/// Splits every triangle into four, adding each edge midpoint (projected onto the unit sphere)
/// once, so that neighbouring triangles keep sharing vertices and the mesh stays closed.
fn subdivide(unit: &mut Vec<Vec3>, triangles: &[[u32; 3]]) -> Vec<[u32; 3]> {
    let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
    let mut midpoint = |a: u32, b: u32, unit: &mut Vec<Vec3>| -> u32 {
        *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
            let p = (unit[a as usize] + unit[b as usize]).normalize();
            unit.push(p);
            (unit.len() - 1) as u32
        })
    };
    let mut out = Vec::with_capacity(triangles.len() * 4);
    for &[a, b, c] in triangles {
        let ab = midpoint(a, b, unit);
        let bc = midpoint(b, c, unit);
        let ca = midpoint(c, a, unit);
        out.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
    }
    out
}
