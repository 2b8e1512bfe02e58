//! Triangle–box overlap by the separating axis theorem (Akenine-Möller 2001): the box and the
//! triangle are disjoint exactly when one of 13 axes separates them (the box's three normals,
//! the triangle's normal, and the nine cross products of box and triangle edges).

use glam::Vec3;

fn project_triangle(axis: Vec3, v: [Vec3; 3]) -> (f32, f32) {
    let p = [axis.dot(v[0]), axis.dot(v[1]), axis.dot(v[2])];
    (p[0].min(p[1]).min(p[2]), p[0].max(p[1]).max(p[2]))
}

/// Whether the triangle `t` overlaps the axis-aligned box of `center` and `half` extent
/// (touching counts as overlapping, so a voxelization built on it is conservative).
pub fn triangle_box_overlap(center: Vec3, half: Vec3, t: [Vec3; 3]) -> bool {
    let v = [t[0] - center, t[1] - center, t[2] - center];
    // Box normals.
    for a in 0..3 {
        let lo = v[0][a].min(v[1][a]).min(v[2][a]);
        let hi = v[0][a].max(v[1][a]).max(v[2][a]);
        if lo > half[a] || hi < -half[a] {
            return false;
        }
    }
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    // Triangle normal.
    let n = e[0].cross(e[1]);
    let r = half.dot(n.abs());
    let d = n.dot(v[0]);
    if d > r || d < -r {
        return false;
    }
    // Edge cross products.
    for edge in e {
        for a in 0..3 {
            let mut unit = Vec3::ZERO;
            unit[a] = 1.0;
            let axis = unit.cross(edge);
            if axis == Vec3::ZERO {
                continue;
            }
            let (lo, hi) = project_triangle(axis, v);
            let r = half.dot(axis.abs());
            if lo > r || hi < -r {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn separating_axes() {
        let c = Vec3::splat(0.5);
        let h = Vec3::splat(0.5);
        let inside = [
            Vec3::new(0.2, 0.2, 0.5),
            Vec3::new(0.8, 0.2, 0.5),
            Vec3::new(0.5, 0.8, 0.5),
        ];
        assert!(triangle_box_overlap(c, h, inside));
        let above = [
            Vec3::new(0.2, 0.2, 1.5),
            Vec3::new(0.8, 0.2, 1.5),
            Vec3::new(0.5, 0.8, 1.5),
        ];
        assert!(!triangle_box_overlap(c, h, above));
        // A large triangle whose plane cuts the box though no vertex is inside.
        let big = [
            Vec3::new(-10.0, -10.0, 0.5),
            Vec3::new(10.0, -10.0, 0.5),
            Vec3::new(0.0, 10.0, 0.5),
        ];
        assert!(triangle_box_overlap(c, h, big));
        // Near a corner, separated only by an edge-cross axis.
        let diag = [
            Vec3::new(1.2, -0.5, 0.5),
            Vec3::new(1.6, 0.1, 0.5),
            Vec3::new(1.4, -0.4, 2.0),
        ];
        assert!(!triangle_box_overlap(c, h, diag));
        // Touching counts.
        let touching = [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        assert!(triangle_box_overlap(c, h, touching));
    }
}
