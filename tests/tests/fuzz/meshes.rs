//! Meshes: OFF and OBJ files through `Mesh::load`, which parses, then validates (indices,
//! finite positions, texture coordinates).

use crate::oracle::{self, MIB};
use crate::{mutate, repo, FileFormat, Seed};
use lazysolid_renderer::mesh::Mesh;
use lazysolid_tests::asset_mesh;
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Bytes a mesh may hold per byte of its file, plus a fixed part: a count in a header must
/// not reserve memory the file cannot fill.
const PER_BYTE: usize = 64;

fn bound(len: usize) -> usize {
    oracle::bound(len, PER_BYTE, 16 * MIB)
}

fn read(path: &Path) -> Result<Mesh, String> {
    Mesh::load(path).map_err(|e| e.to_string())
}

/// The cube and a tetrahedron with comments and a face of four corners in OFF, a plane with
/// texture coordinates and the glint scene's bent quad in OBJ.
/// OBJ statements and OFF header lines with indices, counts and coordinates at their limits.
fn dictionary() -> Vec<String> {
    [
        "OFF",
        "OFF 4 2 0",
        "3 0 1 2",
        "4 0 1 2 3",
        "0 0 0",
        "nan 0 0",
        "1e39 1 1",
        "3 0 0 0",
        "3 0 1 4294967295",
        "2147483648 1 0",
        "-1 -1 -1",
        "v 0 0 0",
        "v nan 1 1",
        "v 1e39 0 0",
        "vt 0.5",
        "vt 0.5 0.5",
        "vn 0 0 1",
        "f 1 2 3",
        "f 1/1 2/2 3/3",
        "f 1//1 2//1 3//1",
        "f -1 -2 -3",
        "f 0 0 0",
        "f 99999 1 2",
        "f 1 2",
        "f 1 1 1",
        "f 1/9 2/9 3/9",
        "o part",
        "g cut",
        "s 1",
        "usemtl m",
        "mtllib missing.mtl",
        "mtllib ../../etc/passwd",
        "l 1 2",
    ]
    .map(String::from)
    .to_vec()
}

fn seeds() -> &'static [Seed] {
    static SEEDS: OnceLock<Vec<Seed>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        vec![
            Seed::file(&asset_mesh("cube.off")),
            Seed {
                name: "pyramid.off".into(),
                bytes: b"OFF\n# a square pyramid\n5 5 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n\
                    4 3 2 1 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n"
                    .to_vec(),
            },
            Seed::file(&repo().join("scenes/normal-maps/plane.obj")),
            Seed::file(&repo().join("scenes/glints/bent_quad.obj")),
        ]
    })
}

/// How the tests read this format.
const FORMAT: FileFormat = FileFormat {
    name: "meshes",
    read: |p| read(p).map(|_| ()),
    bound,
};

fixed_tests!(FORMAT, seeds());

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_meshes(seed in 0..seeds().len(), edits in mutate::mutations_with(dictionary())) {
        let s = &seeds()[seed];
        let bytes = mutate::apply(&s.bytes, &edits);
        FORMAT.case(&s.name, &bytes)?;
    }
}
