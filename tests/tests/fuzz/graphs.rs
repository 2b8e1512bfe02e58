//! Exemplar graphs of multiscale synthesis (`ExemplarGraph::load`): the TOML files of
//! `lazysolid multiscale` and `zoom`, their exemplars named as assets.

use crate::oracle::{self, MIB};
use crate::{mutate, repo, FileFormat, Seed};
use lazysolid_synth::multiscale::ExemplarGraph;
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// What a graph may hold beyond its exemplars' pixels.
const BOUND: usize = 64 * MIB;

/// An `image` value as the command resolves it: an asset name, or a path beside the graph.
fn resolve(graph: &Path, value: &str) -> Result<PathBuf, String> {
    if value.contains('/') || value.contains('.') {
        return Ok(graph.parent().unwrap().join(value));
    }
    let asset = repo().join("assets/exemplars").join(format!("{value}.pat"));
    if asset.exists() {
        Ok(asset)
    } else {
        Err(format!("no exemplar asset named {value}"))
    }
}

fn read(path: &Path) -> Result<ExemplarGraph, String> {
    ExemplarGraph::load(path, &|v| resolve(path, v)).map_err(|e| e.to_string())
}

/// The graph's keys and tables (`synth/src/multiscale/graph.rs`).
const KEYS: &[&str] = &[
    "root",
    "name",
    "image",
    "source",
    "destination",
    "r",
    "finest",
];
const TABLES: &[&str] = &["[[exemplar]]", "[[edge]]"];

fn seeds() -> &'static [Seed] {
    static SEEDS: OnceLock<Vec<Seed>> = OnceLock::new();
    SEEDS.get_or_init(|| {
        [
            "parquet_walnut.toml",
            "marble_loop.toml",
            "marble_single.toml",
        ]
        .iter()
        .map(|f| Seed::file(&repo().join("scenes/multiscale").join(f)))
        .collect()
    })
}

/// How the tests read this format.
const FORMAT: FileFormat = FileFormat {
    name: "graphs",
    read: |p| read(p).map(|_| ()),
    bound: |_| BOUND,
};

fixed_tests!(FORMAT, seeds());

proptest! {
    #![proptest_config(oracle::config_for(seeds().len()))]

    #[test]
    fn mutated_graphs(
        seed in 0..seeds().len(),
        edits in mutate::mutations_with(mutate::toml_dictionary(KEYS, TABLES)),
    ) {
        let s = &seeds()[seed];
        let bytes = mutate::apply(&s.bytes, &edits);
        FORMAT.case(&s.name, &bytes)?;
    }
}
