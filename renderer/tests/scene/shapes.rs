//! The built-in shapes (`shape = "cube" | "sphere" | "quad"`): closed where they bound a solid,
//! facing outwards, and of the unit size the scene's transforms assume.

use glam::{Vec3, Vec3A};
use lazysolid_renderer::mesh::{Mesh, MAX_ICOSPHERE_SUBDIVISIONS};
use std::collections::HashMap;

/// Signed volume (positive when the triangles face outwards) and whether every edge is shared
/// by exactly one other triangle running it the other way (closed and consistently oriented).
fn volume_and_closed(m: &Mesh) -> (f64, bool) {
    let mut volume6 = 0.0f64;
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for &[a, b, c] in &m.triangles {
        let [pa, pb, pc] = [a, b, c].map(|i| m.positions[i as usize].as_dvec3());
        volume6 += pa.dot(pb.cross(pc));
        for (u, v) in [(a, b), (b, c), (c, a)] {
            *edges.entry((u, v)).or_default() += 1;
        }
    }
    let closed = edges
        .iter()
        .all(|(&(u, v), &n)| n == 1 && edges.get(&(v, u)) == Some(&1));
    (volume6 / 6.0, closed)
}

#[test]
fn cube_is_closed_outward_and_unit() {
    let cube = Mesh::unit_cube();
    cube.validate().unwrap();
    assert_eq!((cube.positions.len(), cube.triangles.len()), (8, 12));
    let (volume, closed) = volume_and_closed(&cube);
    assert_eq!(volume, 1.0);
    assert!(closed);
    let b = cube.bounds();
    assert_eq!((b.min, b.max), (Vec3::ZERO, Vec3::ONE));
}

#[test]
fn icosphere_is_closed_outward_and_round() {
    let centre = Vec3A::splat(0.5);
    for s in 0..=4 {
        let sphere = Mesh::icosphere(s);
        sphere.validate().unwrap();
        let n = 4usize.pow(s);
        assert_eq!(
            (sphere.positions.len(), sphere.triangles.len()),
            (10 * n + 2, 20 * n)
        );
        let (volume, closed) = volume_and_closed(&sphere);
        assert!(closed, "subdivisions {s}");
        // Inscribed in the sphere of radius 0.5: below its volume, approaching it.
        let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
        assert!(volume > 0.6 * ball && volume < ball, "{s}: {volume}");
        for p in &sphere.positions {
            let r = (Vec3A::from(*p) - centre).length();
            assert!((r - 0.5).abs() < 1e-6, "{s}: {p} at {r}");
        }
        for &[a, b, c] in &sphere.triangles {
            let [pa, pb, pc] = [a, b, c].map(|i| Vec3A::from(sphere.positions[i as usize]));
            let normal = (pb - pa).cross(pc - pa);
            assert!(normal.dot((pa + pb + pc) / 3.0 - centre) > 0.0, "{s}");
        }
    }
    let (v4, _) = volume_and_closed(&Mesh::icosphere(4));
    let ball = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    assert!((v4 - ball).abs() / ball < 0.01, "{v4} vs {ball}");
    assert_eq!(MAX_ICOSPHERE_SUBDIVISIONS, 7);
}

#[test]
fn quad_faces_up_with_unit_area() {
    let quad = Mesh::unit_quad();
    quad.validate().unwrap();
    assert_eq!((quad.positions.len(), quad.triangles.len()), (4, 2));
    let mut area = Vec3::ZERO;
    for &[a, b, c] in &quad.triangles {
        let [pa, pb, pc] = [a, b, c].map(|i| quad.positions[i as usize]);
        area += (pb - pa).cross(pc - pa) * 0.5;
    }
    assert_eq!(area, Vec3::Y);
    let b = quad.bounds();
    assert_eq!((b.min, b.max), (Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)));
}
