//! `lazysolid fracture`: closed OBJ pieces whose volumes add up to the mesh's, plane cuts, and
//! bad input refused before anything is written.

use crate::support::{lazysolid, repo, run};

/// `lazysolid fracture` writes closed pieces (each OBJ read back and checked) with the cut faces
/// in their own group and material and volumes that add up to the mesh's; plane cuts report a
/// plane that misses; open meshes, bad piece counts and bad planes are refused clearly, and
/// a refused run writes nothing. A self-intersecting scan (the cow) breaks into closed pieces
/// with the resolved crossings reported and the sheets that met at an edge separated.
#[test]
fn fracture_writes_closed_obj_pieces_and_refuses_bad_input() {
    use lazysolid_renderer::fracture::{check_closed, edge_report, volume};
    use lazysolid_renderer::mesh::Mesh;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pieces");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "elephant",
            "--pieces",
            "6",
            "--seed",
            "4",
            "--out-dir",
        ])
        .arg(&out));
    assert!(ok, "{err}");
    assert!(stdout.contains("6 pieces of"), "{stdout}");
    let whole = Mesh::load(repo("assets/meshes/elephant.off")).unwrap();
    let mut sum = 0.0;
    for i in 0..6 {
        let path = out.join(format!("piece_{i:03}.obj"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("mtllib fragments.mtl"), "{text:.200}");
        assert!(text.contains("g interior\nusemtl interior\n"), "piece {i}");
        assert!(text.contains("g surface\nusemtl surface\n"), "piece {i}");
        let piece = Mesh::load(&path).unwrap();
        check_closed(&piece).unwrap();
        sum += volume(&piece.positions, &piece.triangles);
    }
    assert!(!out.join("piece_006.obj").exists());
    let v = volume(&whole.positions, &whole.triangles);
    assert!(((sum - v) / v).abs() < 1e-5, "{sum} vs {v}");
    let mtl = std::fs::read_to_string(out.join("fragments.mtl")).unwrap();
    assert!(mtl.contains("newmtl interior") && mtl.contains("newmtl surface"));

    // A scan whose surface intersects itself: the crossings are resolved and reported.
    let cow = dir.path().join("cow");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "cow",
            "--pieces",
            "12",
            "--seed",
            "1",
            "--out-dir",
        ])
        .arg(&cow));
    assert!(ok, "{err}");
    assert!(
        stdout.contains("22 crossing(s) of cut segments resolved"),
        "{stdout}"
    );
    // Piece 8 of this seed had an edge used by four triangles: its two sheets now have a copy
    // each of the edge's ends, and the files keep the copies apart.
    assert!(
        stdout.contains("separated them with 2 vertex copies and 0 edge splits"),
        "{stdout}"
    );
    for i in 0..12 {
        let piece = Mesh::load(cow.join(format!("piece_{i:03}.obj"))).unwrap();
        check_closed(&piece).unwrap();
        let edges = edge_report(&piece.triangles);
        assert_eq!(edges.shared_edges, 0, "piece {i}: {edges:?}");
    }

    let cut = dir.path().join("cut");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "cube",
            "--plane",
            "0,1,0,5",
            "--plane",
            "1,0,0,0.5",
            "--out-dir",
        ])
        .arg(&cut));
    assert!(ok, "{err}");
    assert!(stdout.contains("(plane 1) misses the mesh"), "{stdout}");
    assert!(
        stdout.contains("75.0000 %") && stdout.contains("25.0000 %"),
        "{stdout}"
    );

    let refused = dir.path().join("refused");
    for (args, needles) in [
        (
            vec!["fracture", "ChineseDragon-10kv", "--pieces", "4"],
            vec!["ChineseDragon-10kv.off", "not closed", "6 boundary edge"],
        ),
        (
            vec!["fracture", "cube", "--pieces", "0"],
            vec!["--pieces 0", "1 to 1024"],
        ),
        (
            vec!["fracture", "cube", "--plane", "0,0,0,1"],
            vec!["non-zero normal"],
        ),
        (vec!["fracture", "cube"], vec!["--pieces N", "--plane"]),
        (
            vec!["fracture", "no_such_mesh", "--pieces", "2"],
            vec!["no_such_mesh"],
        ),
    ] {
        let (ok, _, err) = run(lazysolid().args(&args).arg("--out-dir").arg(&refused));
        assert!(!ok, "{args:?} must fail");
        for n in needles {
            assert!(err.contains(n), "{args:?}: {n:?} not in {err}");
        }
        assert!(!refused.exists(), "{args:?} wrote {}", refused.display());
    }
}

/// `--matter` exports the pieces with their matter where the OBJ pieces go: a glTF binary and
/// OBJ + atlas per piece, in the mesh's own coordinates (the exported pieces' volumes add up
/// to the mesh's), with the bake's figures printed.
#[test]
fn fracture_exports_pieces_with_their_matter() {
    use lazysolid_renderer::fracture::volume;
    use lazysolid_renderer::mesh::Mesh;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("pieces");
    let (ok, stdout, err) = run(lazysolid()
        .args([
            "fracture",
            "elephant",
            "--pieces",
            "4",
            "--seed",
            "2",
            "--matter",
            "leather",
            "--matter-res",
            "16",
            "--out-dir",
        ])
        .arg(&out));
    assert!(ok, "{err}");
    assert!(
        stdout.contains("matter: leather at R = 16 baked in"),
        "{stdout}"
    );
    assert!(stdout.contains("(4 pieces, 16 texels per unit"), "{stdout}");
    let glb = std::fs::read(out.join("elephant.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let whole = Mesh::load(repo("assets/meshes/elephant.off")).unwrap();
    let mut sum = 0.0;
    for i in 0..4 {
        let piece = Mesh::load(out.join(format!("elephant/piece_{i:03}.obj"))).unwrap();
        assert!(piece.uvs.is_some(), "piece {i} has texture coordinates");
        assert!(out.join(format!("elephant/piece_{i:03}.png")).exists());
        sum += volume(&piece.positions, &piece.triangles);
    }
    let v = volume(&whole.positions, &whole.triangles);
    assert!(((sum - v) / v).abs() < 1e-4, "{sum} vs {v}");
}
