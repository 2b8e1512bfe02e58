//! Normal and height maps of the normal-map and glint materials (`load_normal_map`,
//! `load_height_map`): PNG of any depth and layout, fitted to the square power-of-two grid
//! their pyramids need.

use crate::oracle::{self, MIB};
use crate::{mutate, repo, write_case, FileFormat, Seed};
use lazysolid_renderer::glint::example::{load_height_map, load_normal_map};
use lazysolid_synth::MAX_DECODE_SIDE;
use proptest::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// The most a map may hold for a header's size fields: a [`MAX_DECODE_SIDE`]² image of
/// 16-bit RGBA as decoded, its `f32` RGB copy and the fitted map's normals.
const BOUND: usize = (MAX_DECODE_SIDE as usize).pow(2) * (8 + 12 + 8) + 64 * MIB;

/// Reads the file both ways: any image is a height map, and the normal-map reader must refuse
/// a texel outside the unit disc with its position.
fn read(path: &Path) -> Result<(), String> {
    let heights = load_height_map(path, 2.0).map(|_| ());
    load_normal_map(path)?;
    heights
}

/// The maps the scenes use: a grey 8-bit height map, an RGB normal map and a 16-bit grey
/// height map.
fn seeds() -> &'static [Seed] {
    static SEEDS: OnceLock<Vec<Seed>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        [
            "scenes/normal-maps/bumps.png",
            "scenes/normal-maps/v-grooves.png",
            "scenes/glints/scratches.png",
        ]
        .iter()
        .map(|f| Seed::file(&repo().join(f)))
        .collect()
    })
}

#[test]
fn the_seeds_are_read() {
    for s in seeds() {
        let (_dir, path) = write_case(&s.name, &s.bytes);
        let read = if s.name.starts_with("v-grooves") {
            load_normal_map(&path).map(|_| ())
        } else {
            load_height_map(&path, 2.0).map(|_| ())
        };
        read.unwrap_or_else(|e| panic!("seed {}: {e}", s.name));
    }
}

/// How the tests read this format.
const FORMAT: FileFormat = FileFormat {
    name: "maps",
    read,
    bound: |_| BOUND,
};

#[test]
fn regression_cases() {
    FORMAT.replay_regressions();
}

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_maps(
        seed in 0..seeds().len(),
        edits in mutate::mutations(),
        checksums in any::<bool>(),
    ) {
        let s = &seeds()[seed];
        let mut bytes = mutate::apply(&s.bytes, &edits);
        if checksums && s.name.ends_with(".png") {
            mutate::fix_png_checksums(&mut bytes);
        }
        FORMAT.case(&s.name, &bytes)?;
    }
}
