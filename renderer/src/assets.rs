//! The asset folder (meshes and exemplars fetched by `scripts/fetch-assets.sh`), found the
//! same way by every command and by scenes that name an exemplar: first found,
//! 1. `LAZYSOLID_ASSETS`, when set (it must then exist);
//! 2. the `assets/` folder of the repository the executable was built in, found by walking up
//!    from the executable (`target/release/lazysolid` → `assets/`);
//! 3. an `assets/` folder in the current folder or one of its parents.

use std::path::{Path, PathBuf};

/// Environment variable naming the asset folder (the one holding `meshes/` and `exemplars/`).
pub const ASSETS_ENV: &str = "LAZYSOLID_ASSETS";

/// The asset folder by the rule above, or an error saying where it looked.
pub fn asset_root() -> Result<PathBuf, String> {
    if let Some(dir) = std::env::var_os(ASSETS_ENV).filter(|d| !d.is_empty()) {
        let dir = PathBuf::from(dir);
        if !dir.is_dir() {
            return Err(format!("{ASSETS_ENV}={}: no such folder", dir.display()));
        }
        return Ok(dir);
    }
    let mut starts = Vec::new();
    if let Some(exe_dir) = std::env::current_exe()
        .ok()
        .and_then(|e| e.parent().map(Path::to_path_buf))
    {
        starts.push(exe_dir);
    }
    if let Ok(cwd) = std::env::current_dir() {
        starts.push(cwd);
    }
    for start in &starts {
        if let Some(dir) = start
            .ancestors()
            .map(|a| a.join("assets"))
            .find(|a| a.is_dir())
        {
            return Ok(dir);
        }
    }
    Err(format!(
        "no assets/ folder above {} (set {ASSETS_ENV}, or run scripts/fetch-assets.sh in the \
         repository)",
        starts
            .iter()
            .map(|s| s.display().to_string())
            .collect::<Vec<_>>()
            .join(" or ")
    ))
}

/// Whether `value` names a file rather than an asset: it holds a path separator or a `.`.
pub fn is_path(value: &str) -> bool {
    value.contains(['/', '\\', '.'])
}

/// The exemplar a scene names: a path relative to the scene's folder `base`, or an asset name
/// (`leather` is `<assets>/exemplars/leather.pat`). `Err` says where the name was looked for.
pub fn exemplar(value: &str, base: &Path) -> Result<PathBuf, String> {
    if is_path(value) {
        return Ok(base.join(value));
    }
    let dir = asset_root()?.join("exemplars");
    let path = dir.join(format!("{value}.pat"));
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!(
            "no exemplar named {value:?} in {} (give a path relative to the scene, or run \
             scripts/fetch-assets.sh)",
            dir.display()
        ))
    }
}
