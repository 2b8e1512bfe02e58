//! `[[fracture]]` and `[[cut]]`: the named instance replaced by closed pieces of its mesh, the
//! errors of both tables (and of `[explosion]` and `[animation]` without pieces to move), and
//! names that find the right instance among unnamed ones.

use crate::support::{broken, error, expect, parse, BASE};

/// `[[fracture]]` and `[[cut]]` replace the named instance by closed pieces of its mesh (in its
/// coordinates, cap faces marked) whose volumes add up to the mesh's; everything else stays.
#[test]
fn fractures_and_cuts_replace_the_instance_by_closed_pieces() {
    use lazysolid_renderer::fracture::{edge_report, volume};
    for (more, pieces) in [
        ("[[fracture]]\ninstance = \"b\"\npieces = 5\nseed = 4\n", 5),
        (
            "[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.3, 0.5]\nnormal = [0, 1, 0]\n\
             [[cut]]\ninstance = \"b\"\npoint = [0.4, 0.5, 0.5]\nnormal = [1, 0, 0.2]\n",
            4,
        ),
        (
            "[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.5, 0.5]\nnormal = [0, 0, 1]\n\
             [[fracture]]\ninstance = \"b\"\nsites = [[0.2, 0.5, 0.5], [0.8, 0.5, 0.5]]\n",
            4,
        ),
    ] {
        let s = parse(&broken(more)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.instances.len(), pieces, "{more}");
        let mut sum = 0.0;
        for inst in &s.instances {
            let piece = inst.piece.expect("every instance is a piece");
            assert_eq!(piece.broken, 0);
            let m = &s.meshes[inst.mesh];
            let (from, caps) = m.cut_from.as_ref().expect("cut from the box");
            assert_eq!(*from, 0);
            assert_eq!(caps.len(), m.mesh.triangles.len());
            assert!(caps.iter().any(|&c| c) && caps.iter().any(|&c| !c));
            assert!(edge_report(&m.mesh.triangles).is_closed(), "{more}");
            sum += volume(&m.mesh.positions, &m.mesh.triangles);
        }
        assert!((sum - 1.0).abs() < 1e-5, "{more}: volumes sum to {sum}");
    }
}

#[test]
fn fracture_errors_name_the_line_and_field() {
    expect(
        &broken("[[fracture]]\ninstance = \"x\"\npieces = 2\n"),
        21,
        "fracture #1.instance: unknown instance \"x\" (named instances: \"b\")",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\npieces = 0\n"),
        22,
        "fracture #1.pieces",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\npieces = 2\nsites = [[0, 0, 0]]\n"),
        23,
        "fracture #1.sites: pieces and sites are exclusive",
    );
    expect(
        &broken("[[fracture]]\ninstance = \"b\"\n"),
        21,
        "fracture #1: needs pieces = N (random sites) or sites",
    );
    expect(
        &broken("[[cut]]\ninstance = \"b\"\npoint = [0.5, 3, 0.5]\nnormal = [0, 1, 0]\n"),
        22,
        "cut #1.point: the plane through [0.5, 3, 0.5] with normal [0, 1, 0] misses the mesh",
    );
    expect(
        &broken("[[cut]]\ninstance = \"b\"\npoint = [0.5, 0.5, 0.5]\nnormal = [0, 0, 0]\n"),
        23,
        "cut #1.normal: must not be zero",
    );
    expect(
        &broken("[explosion]\nspeed = 1\n"),
        20,
        "explosion: nothing to blow apart",
    );
    expect(
        &broken("[animation]\nframes = 4\nfps = 0\n"),
        22,
        "animation.fps",
    );
    // An open surface bounds no solid: the quad has 4 boundary edges.
    let open = BASE.replace("shape = \"cube\"", "shape = \"quad\"");
    let e = error(&format!(
        "{open}name = \"b\"\n[[fracture]]\ninstance = \"b\"\npieces = 2\n"
    ));
    assert!(
        e.contains("not closed") && e.contains("4 boundary edge"),
        "{e}"
    );
}

/// Names refer to the named instance wherever it stands among unnamed ones; a name used twice
/// is refused at its second use.
#[test]
fn instance_names_find_the_right_instance() {
    let text = format!(
        "{BASE}[[instance]]\nname = \"b\"\nmesh = \"box\"\nmaterial = \"white\"\ntranslate = [3, 0, 0]\n\
         [[fracture]]\ninstance = \"b\"\npieces = 2\n"
    );
    let s = parse(&text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.instances.len(), 3);
    assert!(
        s.instances[0].piece.is_none(),
        "the unnamed box stays whole"
    );
    for inst in &s.instances[1..] {
        assert_eq!(inst.piece.unwrap().broken, 1);
        assert_eq!(inst.transform.translation.x, 3.0);
    }
    let twice = format!(
        "{BASE}name = \"b\"\n[[instance]]\nname = \"b\"\nmesh = \"box\"\nmaterial = \"white\"\n"
    );
    expect(
        &twice,
        21,
        "instance #2.name: duplicate name: instance \"b\" is already defined on line 19",
    );
}
