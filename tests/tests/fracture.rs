//! Fracture geometry on the real meshes and on degenerate cases built by hand: every piece of
//! every plane split and Voronoi fracture is closed (no boundary or non-manifold edge) and the
//! pieces' volumes add up to the mesh's; cap flags survive later cuts; same seed, same pieces;
//! open meshes and bad inputs get errors that name the mesh and count what is wrong.

use glam::{DVec3, Vec3};
use lazysolid_renderer::fracture::{
    check_closed, check_closed_parts, edge_report, fracture, fracture_cells,
    fracture_cells_flagged, random_sites, split_mesh, volume, FractureError, Fragment, Plane, Side,
    SplitResult,
};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::asset_mesh;
use std::path::Path;
use std::time::Instant;

const MESHES: [&str; 5] = [
    "armadillo.off",
    "bunny00.off",
    "ChineseDragon-10kv.off",
    "elephant.off",
    "cube.off",
];

fn load(name: &str) -> Mesh {
    Mesh::load(asset_mesh(name)).unwrap()
}

fn closed_meshes() -> Vec<Mesh> {
    MESHES
        .iter()
        .map(|n| load(n))
        .filter(|m| check_closed(m).is_ok())
        .collect()
}

/// Every piece is closed with no edge shared by four triangles; those of a surface without
/// self-intersections also resolve no crossing and separate no sheets, while those of a
/// self-intersecting one may (`tests/manifold.rs` checks every piece's vertices as well).
#[derive(Clone, Copy, PartialEq)]
enum Expect {
    Manifold,
    Closed,
}

/// What a mesh's pieces must be: the test meshes made or chosen to intersect themselves are
/// named so.
fn expect(what: &str) -> Expect {
    if ["cow", "two-shells"].iter().any(|n| what.contains(n)) {
        Expect::Closed
    } else {
        Expect::Manifold
    }
}

fn assert_closed(f: &Fragment, what: &str) {
    let r = edge_report(&f.triangles);
    assert!(r.is_closed(), "{what}: {r:?}");
    // Sheets that meet at an edge are separated, so no piece shares an edge (tests/manifold.rs
    // checks vertices too).
    assert_eq!(r.shared_edges, 0, "{what}: {r:?}");
    if expect(what) == Expect::Manifold {
        assert_eq!(f.resolved_crossings, 0, "{what}");
    }
    assert_eq!(f.interior.len(), f.triangles.len(), "{what}: flags");
    check_closed_parts(&f.positions, &f.triangles, Path::new(what)).unwrap();
}

fn centre(m: &Mesh) -> DVec3 {
    let (lo, hi) = m
        .positions
        .iter()
        .fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| {
            (lo.min(p.as_dvec3()), hi.max(p.as_dvec3()))
        });
    (lo + hi) * 0.5
}

#[test]
fn report_closedness() {
    for name in MESHES {
        let m = load(name);
        let r = edge_report(&m.triangles);
        println!(
            "{name}: {} vertices, {} triangles, boundary edges {}, non-manifold edges {}, closed {}, volume {:.6e}",
            m.positions.len(),
            m.triangles.len(),
            r.boundary_edges,
            r.non_manifold_edges,
            check_closed(&m).is_ok(),
            volume(&m.positions, &m.triangles)
        );
    }
    // Everything but the dragon (which has holes) bounds a solid: the tests below run on these.
    let closed: Vec<_> = closed_meshes()
        .iter()
        .map(|m| m.source.file_name().unwrap().to_owned())
        .collect();
    assert_eq!(
        closed,
        ["armadillo.off", "bunny00.off", "elephant.off", "cube.off"],
        "closed meshes"
    );
}

fn normals() -> Vec<DVec3> {
    vec![
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(1.0, -2.0, 0.5),
        DVec3::new(-0.3, 0.1, 0.9),
    ]
}

fn check_split(m: &Mesh, plane: Plane, what: &str) -> Option<(Fragment, Fragment)> {
    let what = &format!("{} {what}", m.source.display());
    let v = volume(&m.positions, &m.triangles);
    match split_mesh(m, None, plane).unwrap_or_else(|e| panic!("{what}: {e}")) {
        SplitResult::Missed { side } => {
            println!("{what}: missed, all {side:?}");
            None
        }
        SplitResult::Split { below, above } => {
            assert_closed(&below, &format!("{what} below"));
            assert_closed(&above, &format!("{what} above"));
            let (vb, va) = (below.volume(), above.volume());
            let err = ((vb + va) - v).abs() / v.abs();
            println!(
                "{what}: below {} tris ({} cap) vol {vb:.6e}, above {} tris vol {va:.6e}, rel err {err:.2e}",
                below.triangles.len(),
                below.interior.iter().filter(|&&f| f).count(),
                above.triangles.len()
            );
            assert!(err < 1e-4, "{what}: volume error {err}");
            assert!(vb > 0.0 && va > 0.0, "{what}: {vb} {va}");
            Some((below, above))
        }
    }
}

#[test]
fn plane_splits_through_centre() {
    for m in closed_meshes() {
        let c = centre(&m);
        for n in normals() {
            let what = format!("{} n={n:?}", m.source.file_name().unwrap().display());
            check_split(&m, Plane::through(c, n), &what).expect("centre plane must cut");
        }
    }
}

#[test]
fn plane_splits_through_vertices() {
    // Planes through existing vertices (exact zero distances) with axis normals.
    for m in closed_meshes() {
        for (k, n) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
            for vi in [0usize, m.positions.len() / 2, m.positions.len() / 3] {
                let p = m.positions[vi].as_dvec3();
                let what = format!(
                    "{} axis {k} through vertex {vi}",
                    m.source.file_name().unwrap().display()
                );
                check_split(&m, Plane::through(p, n), &what);
            }
        }
    }
}

#[test]
fn successive_splits_keep_flags() {
    for m in closed_meshes() {
        let c = centre(&m);
        let (below, _) = check_split(&m, Plane::through(c, DVec3::X), "first").unwrap();
        let caps_before = below.interior.iter().filter(|&&f| f).count();
        let SplitResult::Split {
            below: b2,
            above: a2,
        } = below
            .split(Plane::through(c, DVec3::new(0.2, 1.0, 0.1)), &m.source)
            .unwrap()
        else {
            panic!("second cut missed")
        };
        assert_closed(&b2, "second below");
        assert_closed(&a2, "second above");
        let err = (b2.volume() + a2.volume() - below.volume()).abs() / below.volume();
        assert!(err < 1e-4);
        let caps_after = b2
            .interior
            .iter()
            .chain(&a2.interior)
            .filter(|&&f| f)
            .count();
        assert!(caps_after > caps_before, "{caps_after} <= {caps_before}");
    }
}

fn check_fracture(m: &Mesh, n: usize, seed: u64) -> (Vec<Fragment>, f64) {
    let name = m.source.to_string_lossy().into_owned();
    let sites = random_sites(m, n, seed).unwrap();
    let t = Instant::now();
    let pieces = fracture(m, &sites).unwrap_or_else(|e| panic!("{name} {n}: {e}"));
    let secs = t.elapsed().as_secs_f64();
    let v = volume(&m.positions, &m.triangles);
    let mut sum = 0.0;
    for (i, p) in pieces.iter().enumerate() {
        assert_closed(p, &format!("{name} {n} piece {i}"));
        let pv = p.volume();
        assert!(pv > 0.0, "{name} piece {i} volume {pv}");
        sum += pv;
    }
    let err = (sum - v).abs() / v.abs();
    println!(
        "{name}: {n} sites -> {} pieces, {} tris total, rel vol err {err:.2e}, {secs:.3} s",
        pieces.len(),
        pieces.iter().map(|p| p.triangles.len()).sum::<usize>()
    );
    assert!(err < 1e-4, "{name} {n}: volume error {err}");
    (pieces, secs)
}

#[test]
fn voronoi_fracture_8_and_32() {
    for m in closed_meshes() {
        for n in [8, 32] {
            let (a, _) = check_fracture(&m, n, 7);
            let (b, _) = check_fracture(&m, n, 7);
            assert_eq!(a, b, "not repeatable");
        }
    }
}

#[test]
fn voronoi_more_seeds() {
    for m in closed_meshes() {
        for seed in 1..4 {
            check_fracture(&m, 16, seed);
        }
    }
}

fn cube() -> Mesh {
    load("cube.off")
}

#[test]
fn cube_degenerate_planes() {
    let m = cube();
    // Through the face z = max: misses (touching only).
    let (lo, hi) = m
        .positions
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(*p), b.max(*p)));
    assert_eq!(
        split_mesh(&m, None, Plane::new(DVec3::Z, f64::from(hi.z))).unwrap(),
        SplitResult::Missed { side: Side::Below }
    );
    assert_eq!(
        split_mesh(&m, None, Plane::new(DVec3::Z, f64::from(lo.z))).unwrap(),
        SplitResult::Missed { side: Side::Above }
    );
    assert_eq!(
        split_mesh(&m, None, Plane::new(DVec3::Z, 1e6)).unwrap(),
        SplitResult::Missed { side: Side::Below }
    );
    let c = centre(&m);
    // Diagonal planes through edges and vertices of the cube.
    for n in [
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(0.0, 1.0, -1.0),
    ] {
        check_split(&m, Plane::through(c, n), &format!("cube diag {n:?}"));
    }
    // Through a corner along the main diagonal's normal: cuts off a tetrahedron-like corner? No:
    // a plane through vertices (1,-1,-1),(-1,1,-1),(-1,-1,1) cuts a corner with vertices on it.
    let n = DVec3::new(1.0, 1.0, 1.0);
    check_split(
        &m,
        Plane::new(n, n.dot(DVec3::new(1.0, -1.0, -1.0) * f64::from(hi.x))),
        "cube corner",
    );
}

/// The cube and a copy moved by `shift` (two separate shells).
fn two_cubes(shift: Vec3) -> Mesh {
    let m = cube();
    let mut positions = m.positions.clone();
    let n0 = positions.len() as u32;
    positions.extend(m.positions.iter().map(|p| *p + shift));
    let mut triangles = m.triangles.clone();
    triangles.extend(m.triangles.iter().map(|t| t.map(|i| i + n0)));
    let two = Mesh {
        positions,
        triangles,
        uvs: None,
        source: "two-cubes".into(),
    };
    check_closed(&two).unwrap();
    two
}

#[test]
fn touching_loops_and_coplanar_faces() {
    // Cubes (side 2, centred at 0) touching along an edge: planes through the shared edge and
    // through the coplanar faces.
    let two = two_cubes(Vec3::new(2.0, 2.0, 0.0));
    check_split(&two, Plane::new(DVec3::X, 1.0), "edge-touching cubes x=1");
    check_split(
        &two,
        Plane::new(DVec3::new(1.0, 1.0, 0.0), 2.0),
        "edge-touching cubes x+y=2",
    );
    check_split(&two, Plane::new(DVec3::Z, 0.0), "edge-touching cubes z=0");
    check_split(
        &two,
        Plane::new(DVec3::Z, 1.0),
        "edge-touching cubes z=1 (top faces)",
    );
    // Cubes touching at one corner (1,1,1), cut through it: the two cross-sections touch at a
    // point, which the cap welds into one vertex.
    let two = two_cubes(Vec3::splat(2.0));
    check_split(
        &two,
        Plane::new(DVec3::new(1.0, -1.0, 0.0), 0.0),
        "corner-touching cubes x=y",
    );
    check_split(
        &two,
        Plane::new(DVec3::new(0.0, 1.0, -1.0), 0.0),
        "corner-touching cubes y=z",
    );
}

#[test]
fn errors_are_clear() {
    let m = cube();
    let mut open = m.clone();
    open.triangles.pop();
    open.source = "open-cube.off".into();
    let e = split_mesh(&open, None, Plane::new(DVec3::Z, 0.0)).unwrap_err();
    assert_eq!(
        e,
        FractureError::NotClosed {
            mesh: "open-cube.off".into(),
            boundary_edges: 3,
            non_manifold_edges: 0
        }
    );
    assert!(e.to_string().contains("open-cube.off"), "{e}");
    let mut flipped = m.clone();
    flipped.triangles[0].swap(1, 2);
    assert!(matches!(
        check_closed(&flipped),
        Err(FractureError::NotClosed {
            non_manifold_edges: 3,
            ..
        })
    ));
    assert!(matches!(
        split_mesh(&m, None, Plane::new(DVec3::ZERO, 0.0)),
        Err(FractureError::InvalidPlane { .. })
    ));
    assert!(matches!(
        split_mesh(&m, Some(&[true]), Plane::new(DVec3::Z, 0.0)),
        Err(FractureError::FlagCount { .. })
    ));
    assert!(matches!(
        fracture(&m, &[]),
        Err(FractureError::PieceCount { requested: 0, .. })
    ));
    assert!(matches!(
        random_sites(&m, 0, 1),
        Err(FractureError::PieceCount { .. })
    ));
    assert!(matches!(
        random_sites(&m, 100_000, 1),
        Err(FractureError::PieceCount { .. })
    ));
    assert!(matches!(
        fracture(&m, &[Vec3::ZERO, Vec3::X, Vec3::ZERO]),
        Err(FractureError::DuplicateSites {
            first: 0,
            second: 2
        })
    ));
    assert!(matches!(
        fracture(&m, &[Vec3::NAN]),
        Err(FractureError::InvalidSite { index: 0 })
    ));
    let mut bad = m.clone();
    bad.triangles[0][0] = 99;
    assert!(matches!(
        check_closed(&bad),
        Err(FractureError::IndexOutOfRange { .. })
    ));
    let empty = Mesh {
        positions: vec![],
        triangles: vec![],
        uvs: None,
        source: "e".into(),
    };
    assert!(matches!(
        fracture(&empty, &[Vec3::ZERO]),
        Err(FractureError::Empty { .. })
    ));
    // Sites far outside: cells without solid are None, one cell takes everything.
    let cells = fracture_cells(&m, &[Vec3::ZERO, Vec3::splat(100.0)]).unwrap();
    assert!(cells[0].is_some() && cells[1].is_none());
}

#[test]
fn single_site_returns_whole_mesh() {
    let m = cube();
    let pieces = fracture(&m, &[Vec3::ZERO]).unwrap();
    assert_eq!(pieces.len(), 1);
    assert!((pieces[0].volume() - volume(&m.positions, &m.triangles)).abs() < 1e-9);
}

#[test]
fn refracture_a_piece_keeps_flags() {
    let m = load("elephant.off");
    let pieces = fracture(&m, &random_sites(&m, 4, 3).unwrap()).unwrap();
    let piece = &pieces[0];
    let as_mesh = piece.to_mesh("elephant piece 0".into());
    let sites = random_sites(&as_mesh, 5, 9).unwrap();
    let again: Vec<Fragment> = fracture_cells_flagged(&as_mesh, Some(&piece.interior), &sites)
        .unwrap()
        .into_iter()
        .flatten()
        .collect();
    let flagged_before = piece.interior.iter().filter(|&&f| f).count();
    assert!(flagged_before > 0);
    let mut sum = 0.0;
    for (i, p) in again.iter().enumerate() {
        assert_closed(p, &format!("re-fractured {i}"));
        sum += p.volume();
    }
    assert!((sum - piece.volume()).abs() / piece.volume() < 1e-4);
    // Old caps keep their flag: flagged area does not shrink.
    let area = |f: &Fragment| -> f64 {
        f.triangles
            .iter()
            .zip(&f.interior)
            .filter(|(_, i)| **i)
            .map(|(t, _)| {
                let [a, b, c] = t.map(|k| f.positions[k as usize].as_dvec3());
                (b - a).cross(c - a).length() * 0.5
            })
            .sum()
    };
    let after: f64 = again.iter().map(area).sum();
    assert!(after > area(piece), "{after} <= {}", area(piece));
}

#[test]
fn dragon_is_rejected_with_counts() {
    let m = load("ChineseDragon-10kv.off");
    let e = fracture(&m, &[Vec3::ZERO]).unwrap_err();
    println!("{e}");
    assert!(matches!(
        e,
        FractureError::NotClosed {
            boundary_edges: 6,
            non_manifold_edges: 0,
            ..
        }
    ));
    assert!(e.to_string().contains("ChineseDragon-10kv.off"));
}

/// Many pieces and seeds; run with `cargo test -- --ignored` (a few seconds each mesh).
#[test]
#[ignore]
fn stress_many_pieces() {
    for m in closed_meshes() {
        for seed in 10..14 {
            check_fracture(&m, 128, seed);
        }
    }
}

/// The cube and a copy moved by `shift`, scaled by `scale` about its centre, as one mesh: two
/// shells that interpenetrate (or nest) when they overlap, a self-intersecting closed surface.
fn two_shells(shift: Vec3, scale: f32) -> Mesh {
    let m = cube();
    let mut positions = m.positions.clone();
    let n0 = positions.len() as u32;
    positions.extend(m.positions.iter().map(|p| *p * scale + shift));
    let mut triangles = m.triangles.clone();
    triangles.extend(m.triangles.iter().map(|t| t.map(|i| i + n0)));
    let two = Mesh {
        positions,
        triangles,
        uvs: None,
        source: "two-shells".into(),
    };
    check_closed(&two).unwrap();
    two
}

/// Splits and checks like [`check_split`] and returns the crossings the cap resolved.
fn crossings_of_split(m: &Mesh, plane: Plane, what: &str) -> usize {
    let (below, above) = check_split(m, plane, what).expect("the plane must cut");
    assert_eq!(below.resolved_crossings, above.resolved_crossings, "{what}");
    below.resolved_crossings
}

#[test]
fn interpenetrating_shells_are_capped_by_layers() {
    // Overlapping cubes: the cross-section's two squares cross at two points (winding -2 in
    // their overlap); rotated planes make the crossings fall inside segments.
    let m = two_shells(Vec3::new(1.0, 0.7, 0.3), 1.0);
    assert_eq!(
        crossings_of_split(&m, Plane::new(DVec3::Z, 0.1), "overlap z"),
        2
    );
    for (k, n) in normals().into_iter().enumerate() {
        let what = format!("overlap n={n:?}");
        let c = crossings_of_split(&m, Plane::through(DVec3::new(0.5, 0.35, 0.15), n), &what);
        println!("{what}: {c} crossing(s) resolved");
        assert!(c > 0 || k == 0, "{what}: the squares must cross");
    }
    // A smaller cube inside a larger one, both outward: nested loops of the same direction
    // (winding -2 inside, no crossing).
    let nested = two_shells(Vec3::new(0.1, -0.2, 0.05), 0.4);
    assert_eq!(
        crossings_of_split(&nested, Plane::new(DVec3::Z, 0.0), "nested z"),
        0
    );
    // Re-cut a piece through the resolved crossings, and fracture.
    let SplitResult::Split { below, .. } = split_mesh(&m, None, Plane::new(DVec3::Z, 0.1)).unwrap()
    else {
        panic!("missed")
    };
    let SplitResult::Split {
        below: b2,
        above: a2,
    } = below
        .split(Plane::new(DVec3::new(1.0, 1.0, 0.2), 1.0), &m.source)
        .unwrap()
    else {
        panic!("second cut missed")
    };
    assert_closed(&b2, "two-shells overlap second below");
    assert_closed(&a2, "two-shells overlap second above");
    assert!(b2.resolved_crossings >= 2 && a2.resolved_crossings >= 2);
    let err = (b2.volume() + a2.volume() - below.volume()).abs() / below.volume();
    assert!(err < 1e-4, "second cut volume error {err}");
    for seed in 1..=4 {
        check_fracture(&m, 8, seed);
        check_fracture(&nested, 6, seed);
    }
}

#[test]
fn self_intersecting_scan_breaks_into_closed_pieces() {
    // CGAL's cow: closed, but its surface intersects itself (89 of 5,804 faces), so most
    // Voronoi fractures cut through a self-intersection. Every seed must give closed pieces
    // whose (winding-weighted) volumes add up, with the crossings resolved reported.
    let m = load("cow.off");
    check_closed(&m).unwrap();
    let mut total = 0;
    for seed in 1..=8 {
        let (pieces, _) = check_fracture(&m, 12, seed);
        let c: usize = pieces.iter().map(|p| p.resolved_crossings).sum();
        println!("cow seed {seed}: {c} crossing(s) resolved in the caps");
        total += c;
    }
    assert!(total > 0, "no fracture of the cow met a self-intersection");
    let c = centre(&m);
    for n in normals() {
        check_split(&m, Plane::through(c, n), &format!("cow n={n:?}"));
    }
}
