//! NRRD volumes (`VolumeTexture::load`), as `lazysolid solid` writes them and scenes read them
//! as `kind = "volume"` textures.

use crate::oracle::{self, MIB};
use crate::{mutate, FileFormat, Seed};
use lazysolid_renderer::scene::VolumeTexture;
use lazysolid_synth::solid::encode_nrrd;
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// Bytes a volume may hold per byte of its file, plus a fixed part: the header's sizes must
/// agree with the data before anything is allocated for them.
fn bound(len: usize) -> usize {
    oracle::bound(len, 16, 4 * MIB)
}

fn read(path: &Path) -> Result<VolumeTexture, String> {
    VolumeTexture::load(path)
}

/// A 5×4×3 volume with notes, as `solid` writes it, and a one-voxel one.
/// Header fields with the values the reader refuses or must bound.
fn dictionary() -> Vec<String> {
    [
        "type: float",
        "type: uint16",
        "dimension: 3",
        "dimension: 4294967296",
        "sizes: 3 1024 1024 1024",
        "sizes: 3 4294967295 1 1",
        "sizes: 3 0 1 1",
        "sizes: 4 1 1 1",
        "sizes: 3 1 1",
        "sizes: 3 -1 1 1",
        "encoding: gzip",
        "encoding: ascii",
        "endian: big",
        "kinds: domain domain domain domain",
        "space directions: none",
        "key:=value",
        "# note",
        "NRRD0001",
        "NRRD9999",
    ]
    .map(String::from)
    .to_vec()
}

fn seeds() -> &'static [Seed] {
    static SEEDS: OnceLock<Vec<Seed>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let colours: Vec<[u8; 3]> = (0..60u8).map(|i| [i, 255 - i, i.wrapping_mul(7)]).collect();
        // `encode_nrrd` writes cubes; a box of other sides is the same header with its sizes.
        let cube = encode_nrrd(
            &colours[..27],
            3,
            &["seed 3".into(), "exemplar walnut".into()],
        );
        vec![
            Seed {
                name: "cube.nrrd".into(),
                bytes: cube,
            },
            Seed {
                name: "box.nrrd".into(),
                bytes: [
                    b"NRRD0004\n# a box\ntype: uint8\ndimension: 4\nsizes: 3 5 4 3\n\
                      kinds: RGB-color domain domain domain\nencoding: raw\n\n"
                        .as_slice(),
                    colours
                        .iter()
                        .flatten()
                        .copied()
                        .collect::<Vec<u8>>()
                        .as_slice(),
                ]
                .concat(),
            },
            Seed {
                name: "voxel.nrrd".into(),
                bytes: encode_nrrd(&[[1, 2, 3]], 1, &[]),
            },
        ]
    })
}

/// How the tests read this format.
const FORMAT: FileFormat = FileFormat {
    name: "nrrd",
    read: |p| read(p).map(|_| ()),
    bound,
};

fixed_tests!(FORMAT, seeds());

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_volumes(seed in 0..seeds().len(), edits in mutate::mutations_with(dictionary())) {
        let s = &seeds()[seed];
        let bytes = mutate::apply(&s.bytes, &edits);
        FORMAT.case(&s.name, &bytes)?;
    }
}
