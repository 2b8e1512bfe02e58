//! Fracture pieces are closed 2-manifolds, edge- and vertex-manifold, by a check written apart
//! from the fracture code (which counts edges by sorting and never walks around a vertex):
//! here every directed edge is looked up in a hash map, and the triangles around each vertex
//! are walked as a fan. The cow (a scan whose surface intersects itself) and the armadillo
//! are broken with 8 seeds each, the counts the issue names.

use glam::{DVec3, Vec3};
use lazysolid_renderer::fracture::{
    check_closed, cut_pieces, fracture, random_sites, volume, Fragment, Plane,
};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::asset_mesh;
use std::collections::HashMap;

/// What is wrong with a surface as a closed 2-manifold, counted.
#[derive(Debug, Default, PartialEq, Eq)]
struct Defects {
    /// Triangles that use one vertex twice.
    degenerate_triangles: usize,
    /// Directed edges used by more than one triangle.
    repeated_directed_edges: usize,
    /// Directed edges whose reverse no triangle uses (a boundary or a one-sided sheet).
    unmatched_directed_edges: usize,
    /// Vertices whose triangles form more than one fan (two sheets meeting at a point).
    pinched_vertices: usize,
    /// Vertices that no triangle uses.
    unused_vertices: usize,
}

impl Defects {
    fn none(&self) -> bool {
        *self == Defects::default()
    }
}

/// Checks that every directed edge is used exactly once and its reverse exactly once (closed,
/// consistently oriented, no edge shared by more than two triangles), and that the triangles
/// around every vertex form one fan, walked from triangle to triangle across the edges at
/// that vertex.
fn manifold_defects(positions: &[Vec3], triangles: &[[u32; 3]]) -> Defects {
    let mut d = Defects::default();
    let mut owner: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            d.degenerate_triangles += 1;
            continue;
        }
        for k in 0..3 {
            if owner.insert((tri[k], tri[(k + 1) % 3]), t).is_some() {
                d.repeated_directed_edges += 1;
            }
        }
    }
    d.unmatched_directed_edges = owner
        .keys()
        .filter(|(a, b)| !owner.contains_key(&(*b, *a)))
        .count();
    // Triangles around each vertex, then one walk: from a triangle with corner v, whose edge
    // leaving v is v -> x, the next triangle around v is the one that uses x -> v.
    let mut around: HashMap<u32, Vec<usize>> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            around.entry(v).or_default().push(t);
        }
    }
    d.unused_vertices = (0..positions.len() as u32)
        .filter(|v| !around.contains_key(v))
        .count();
    for (&v, fan) in &around {
        let leaving = |t: usize| {
            let tri = triangles[t];
            let k = tri.iter().position(|&i| i == v).unwrap();
            tri[(k + 1) % 3]
        };
        let start = fan[0];
        let mut t = start;
        let mut seen = 0;
        loop {
            seen += 1;
            match owner.get(&(leaving(t), v)) {
                Some(&next) if next != start && seen <= fan.len() => t = next,
                _ => break,
            }
        }
        if seen != fan.len() {
            d.pinched_vertices += 1;
        }
    }
    d
}

fn check(mesh: &str, pieces: usize) {
    let m = Mesh::load(asset_mesh(mesh)).unwrap();
    let mut separated = 0;
    for seed in 1..=8 {
        let sites = random_sites(&m, pieces, seed).unwrap();
        let broken: Vec<Fragment> = fracture(&m, &sites).unwrap();
        for (i, p) in broken.iter().enumerate() {
            let d = manifold_defects(&p.positions, &p.triangles);
            assert!(d.none(), "{mesh} seed {seed} piece {i}: {d:?}");
            separated += p.separated_vertices;
        }
        println!(
            "{mesh} seed {seed}: {} pieces, vertices separated so far {separated}",
            broken.len()
        );
    }
}

#[test]
fn cow_pieces_are_closed_2_manifolds() {
    check("cow.off", 12);
}

#[test]
fn armadillo_pieces_are_closed_2_manifolds() {
    check("armadillo.off", 14);
}

/// A tetrahedron at the origin with unit legs along +x (or -x when `mirrored`), +y and +z,
/// oriented outward.
fn tetrahedron(mirrored: bool) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let x = if mirrored { -Vec3::X } else { Vec3::X };
    let p = vec![Vec3::ZERO, x, Vec3::Y, Vec3::Z];
    let t = if mirrored {
        vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
    } else {
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    };
    (p, t)
}

/// Two tetrahedra on either side of the y-z plane, sharing the origin and, with `edge`, the
/// edge along z as well: closed and consistently oriented, with one pinched vertex or one
/// edge used by four triangles, as the fracture code's closedness check accepts.
fn two_tetrahedra(edge: bool) -> Mesh {
    let (mut positions, mut triangles) = tetrahedron(false);
    let (b, tb) = tetrahedron(true);
    let keep = if edge { 2 } else { 1 }; // shared with the first: vertex 0, and 3 with `edge`
    let base = positions.len() as u32;
    positions.extend(&b[1..4 - keep + 1]);
    triangles.extend(tb.iter().map(|t| {
        t.map(|i| match i {
            0 => 0,
            3 if edge => 3,
            i => base + i - 1,
        })
    }));
    Mesh {
        positions,
        triangles,
        uvs: None,
        source: if edge {
            "tetrahedra-edge"
        } else {
            "tetrahedra-vertex"
        }
        .into(),
    }
}

/// The check itself finds what it is for, on surfaces the fracture code accepts as closed.
#[test]
fn the_check_finds_shared_edges_and_pinched_vertices() {
    let (a, ta) = tetrahedron(false);
    let single = manifold_defects(&a, &ta);
    assert!(single.none(), "{single:?}");
    let pinch = two_tetrahedra(false);
    let d = manifold_defects(&pinch.positions, &pinch.triangles);
    assert_eq!(d.pinched_vertices, 1, "{d:?}");
    assert_eq!(
        d.unmatched_directed_edges + d.repeated_directed_edges,
        0,
        "{d:?}"
    );
    let shared = two_tetrahedra(true);
    let d = manifold_defects(&shared.positions, &shared.triangles);
    assert_eq!(d.repeated_directed_edges, 2, "{d:?}");
    assert_eq!(d.unmatched_directed_edges, 0, "{d:?}");
    for m in [&pinch, &shared] {
        check_closed(m).unwrap();
    }
    let mut open = ta.clone();
    open.pop();
    let open = manifold_defects(&a, &open);
    assert_eq!(open.unmatched_directed_edges, 3, "{open:?}");
}

/// The sheets of the hand-made surfaces are separated: one copy of the pinched vertex, one
/// copy of each end of the shared edge, and positions and volume unchanged.
#[test]
fn sheets_meeting_at_a_vertex_or_an_edge_are_separated() {
    for (edge, copies) in [(false, 1), (true, 2)] {
        let m = two_tetrahedra(edge);
        let pieces = fracture(&m, &[Vec3::new(0.0, 0.2, 0.2)]).unwrap();
        let p = &pieces[0];
        let d = manifold_defects(&p.positions, &p.triangles);
        assert!(d.none(), "{:?}: {d:?}", m.source);
        assert_eq!(p.separated_vertices, copies, "{:?}", m.source);
        assert_eq!(p.split_edges, 0, "{:?}", m.source);
        assert_eq!(p.triangles.len(), m.triangles.len());
        assert_eq!(p.volume(), volume(&m.positions, &m.triangles));
        for (t, u) in p.triangles.iter().zip(&m.triangles) {
            for (i, j) in t.iter().zip(u) {
                assert_eq!(p.positions[*i as usize], m.positions[*j as usize]);
            }
        }
    }
}

/// Plane cuts made one after another (`cut_pieces`, as a scene's `[[cut]]` tables make them)
/// through the cow give 2-manifold pieces too, and so do cuts through the two layers of a
/// cap of interpenetrating boxes.
#[test]
fn successive_plane_cuts_of_a_self_intersecting_scan_are_2_manifolds() {
    let m = Mesh::load(asset_mesh("cow.off")).unwrap();
    let (lo, hi) = m
        .positions
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let c = ((lo + hi) * 0.5).as_dvec3();
    let mut pieces = vec![Fragment::whole(&m)];
    for n in [
        DVec3::X,
        DVec3::new(0.3, 1.0, 0.2),
        DVec3::new(-0.4, 0.1, 1.0),
    ] {
        pieces = cut_pieces(pieces, Plane::through(c, n), &m.source)
            .unwrap()
            .0;
    }
    assert!(pieces.len() >= 6, "{} pieces", pieces.len());
    for (i, p) in pieces.iter().enumerate() {
        let d = manifold_defects(&p.positions, &p.triangles);
        assert!(d.none(), "cow cut piece {i}: {d:?}");
    }
}

/// Two interpenetrating boxes (the cube and a shifted copy, as one surface): their pieces'
/// caps lie over each other, and some sheets meet around both ends of an edge, so the
/// midpoint split is needed as well as the vertex copies.
#[test]
fn pieces_of_interpenetrating_boxes_are_2_manifolds() {
    let cube = Mesh::load(asset_mesh("cube.off")).unwrap();
    let mut two = cube.clone();
    let n = two.positions.len() as u32;
    let shift = Vec3::new(1.0, 0.7, 0.3) * (cube.positions[0] - cube.positions[1]).length();
    let (lo, hi) = cube
        .positions
        .iter()
        .fold((Vec3::MAX, Vec3::MIN), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let shift = shift.normalize() * (hi - lo).length() * 0.45;
    two.positions
        .extend(cube.positions.iter().map(|p| *p + shift));
    two.triangles
        .extend(cube.triangles.iter().map(|t| t.map(|i| i + n)));
    let (mut copies, mut splits) = (0, 0);
    for seed in 1..=4 {
        let sites = random_sites(&two, 8, seed).unwrap();
        for (i, p) in fracture(&two, &sites).unwrap().iter().enumerate() {
            let d = manifold_defects(&p.positions, &p.triangles);
            assert!(d.none(), "two boxes seed {seed} piece {i}: {d:?}");
            copies += p.separated_vertices;
            splits += p.split_edges;
        }
    }
    println!("two boxes: {copies} vertex copies, {splits} edge splits");
    assert!(copies > 0 && splits > 0, "{copies} copies, {splits} splits");
}
