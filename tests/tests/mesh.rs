//! Real meshes (CGAL's, from Debian's libcgal-demo) and malformed ones.

use lazysolid_renderer::mesh::{Mesh, MeshError};
use lazysolid_tests::asset_mesh;
use std::io::Write;

#[test]
fn cgal_meshes_load_with_their_documented_sizes() {
    let armadillo = Mesh::load(asset_mesh("armadillo.off")).unwrap();
    assert_eq!(
        (armadillo.positions.len(), armadillo.triangles.len()),
        (26_002, 52_000)
    );
    let dragon = Mesh::load(asset_mesh("ChineseDragon-10kv.off")).unwrap();
    assert_eq!(
        (dragon.positions.len(), dragon.triangles.len()),
        (10_000, 19_994)
    );
    let bunny = Mesh::load(asset_mesh("bunny00.off")).unwrap();
    assert_eq!(bunny.triangles.len(), 75_408);
}

#[test]
fn normalization_puts_the_longest_axis_on_the_unit_interval() {
    let mut m = Mesh::load(asset_mesh("armadillo.off")).unwrap();
    m.normalize_to_unit_cube();
    let b = m.bounds();
    assert!(
        b.min.min_element() >= -1e-6 && b.max.max_element() <= 1.0 + 1e-6,
        "{b:?}"
    );
    assert!((b.size().max_element() - 1.0).abs() < 1e-5, "{b:?}");
    // The shorter axes are centred.
    let centre = (b.min + b.max) * 0.5;
    assert!(
        (centre - glam::Vec3::splat(0.5)).abs().max_element() < 1e-5,
        "{centre:?}"
    );
}

fn write_temp(name: &str, text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::File::create(&path)
        .unwrap()
        .write_all(text.as_bytes())
        .unwrap();
    (dir, path)
}

#[test]
fn obj_and_off_of_the_same_shape_agree() {
    let (_d1, obj) = write_temp(
        "quad.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let (_d2, off) = write_temp(
        "quad.off",
        "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n",
    );
    let a = Mesh::load(&obj).unwrap();
    let b = Mesh::load(&off).unwrap();
    assert_eq!(a.triangles.len(), 2);
    assert_eq!(a.triangles.len(), b.triangles.len());
    let area = |m: &Mesh| -> f32 {
        m.triangles
            .iter()
            .map(|t| {
                (m.positions[t[1] as usize] - m.positions[t[0] as usize])
                    .cross(m.positions[t[2] as usize] - m.positions[t[0] as usize])
                    .length()
                    * 0.5
            })
            .sum()
    };
    assert!((area(&a) - 1.0).abs() < 1e-6 && (area(&b) - 1.0).abs() < 1e-6);
}

#[test]
fn bad_meshes_get_errors_naming_the_file() {
    let missing = Mesh::load("/no/such/mesh.off").unwrap_err();
    assert!(
        matches!(missing, MeshError::Io { .. })
            && missing.to_string().contains("/no/such/mesh.off"),
        "{missing}"
    );
    let (_d, ply) = write_temp("mesh.ply", "ply\n");
    assert!(matches!(
        Mesh::load(&ply).unwrap_err(),
        MeshError::UnknownFormat { .. }
    ));
    let (_d, empty) = write_temp("empty.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
    let e = Mesh::load(&empty).unwrap_err();
    assert!(
        matches!(e, MeshError::Empty { .. }) && e.to_string().contains("empty.off"),
        "{e}"
    );
    let (_d, bad_obj) = write_temp("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    let e = Mesh::load(&bad_obj).unwrap_err();
    assert!(e.to_string().contains("bad.obj"), "{e}");
    let (_d, truncated) = write_temp("truncated.off", "OFF\n3 1 0\n0 0 0\n");
    let e = Mesh::load(&truncated).unwrap_err().to_string();
    assert!(e.contains("truncated.off") && e.contains("vertex 1"), "{e}");
}
