//! Meshes and exemplars by name, from any folder.
//!
//! A value with a path separator or a `.` is a path (relative to the current folder, as the
//! shell gives it). Any other value is an asset name: `armadillo` is
//! `<assets>/meshes/armadillo.off` (or `.obj`), `leather` is `<assets>/exemplars/leather.pat`.
//! The asset folder is, first found:
//! 1. `LAZYSOLID_ASSETS`, when set (it must then exist);
//! 2. the `assets/` folder of the repository the executable was built in, found by walking up
//!    from the executable (`target/release/lazysolid` → `assets/`);
//! 3. an `assets/` folder in the current folder or one of its parents.

use anyhow::{bail, Context};
use clap::Args;
use lazysolid_synth::multiscale::ExemplarGraph;
use std::path::{Path, PathBuf};

/// The asset folder by the rule above, or an error saying where it looked.
pub fn asset_root() -> anyhow::Result<PathBuf> {
    lazysolid_renderer::assets::asset_root().map_err(anyhow::Error::msg)
}

/// Whether `value` names a file rather than an asset.
fn is_path(value: &str) -> bool {
    value.contains(['/', '\\', '.'])
}

/// The mesh `--mesh value` names: a path as given, or `<assets>/meshes/NAME.off|.obj`.
pub fn mesh(flag: &str, value: &str) -> anyhow::Result<PathBuf> {
    named(flag, value, "meshes", &["off", "obj"], "mesh")
}

/// The exemplar `value` names: a path as given, or `NAME.pat` in `dir` (by default
/// `<assets>/exemplars`).
pub fn exemplar(flag: &str, value: &str, dir: Option<&Path>) -> anyhow::Result<PathBuf> {
    match dir {
        Some(dir) if !is_path(value) => Ok(dir.join(format!("{value}.pat"))),
        _ => named(flag, value, "exemplars", &["pat"], "exemplar"),
    }
}

fn named(
    flag: &str,
    value: &str,
    folder: &str,
    extensions: &[&str],
    what: &str,
) -> anyhow::Result<PathBuf> {
    if is_path(value) {
        return Ok(PathBuf::from(value));
    }
    let dir = asset_root()
        .with_context(|| format!("{flag} {value}: looking for the {what} named {value:?}"))?
        .join(folder);
    if let Some(found) = extensions
        .iter()
        .map(|e| dir.join(format!("{value}.{e}")))
        .find(|p| p.is_file())
    {
        return Ok(found);
    }
    let mut known: Vec<String> = std::fs::read_dir(&dir)
        .into_iter()
        .flatten()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| extensions.iter().any(|e| x.eq_ignore_ascii_case(e)))
        })
        .filter_map(|p| Some(p.file_stem()?.to_string_lossy().into_owned()))
        .collect();
    known.sort();
    bail!(
        "{flag} {value}: no {what} named {value:?} in {} (known: {}); give a path, or run \
         scripts/fetch-assets.sh",
        dir.display(),
        if known.is_empty() {
            "none".to_string()
        } else {
            known.join(", ")
        }
    )
}

/// Where named exemplars live, for the commands that take several or one by name.
#[derive(Args, Clone, Debug, Default)]
pub struct ExemplarDir {
    /// Where named exemplars live; default: the assets' exemplars (scripts/fetch-assets.sh
    /// fills them), found as every other command finds them
    #[arg(long = "exemplar-dir", value_name = "DIR")]
    pub path: Option<PathBuf>,
}

/// Loads the graph, resolving images as asset names or paths relative to the graph file.
pub fn load_graph(path: &Path) -> anyhow::Result<ExemplarGraph> {
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let resolve = |value: &str| -> Result<PathBuf, String> {
        if value.contains(['/', '\\', '.']) {
            Ok(dir.join(value))
        } else {
            exemplar("image", value, None).map_err(|e| format!("{e:#}"))
        }
    };
    Ok(ExemplarGraph::load(path, &resolve)?)
}
