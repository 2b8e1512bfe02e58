//! Output files: checked before the work that fills them starts, and written whole or not at
//! all.

use anyhow::{bail, Context};
use lazysolid_compute::atomic_file;
use std::path::{Path, PathBuf};

/// The folder `path` goes into (`.` for a bare file name).
fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Creates and removes an empty file in `folder`: the one test of "can a file be made here"
/// that covers permissions, read-only mounts and full inode tables alike.
fn probe(folder: &Path) -> std::io::Result<()> {
    let probe = folder.join(format!(".lazysolid-probe-{}", std::process::id()));
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)?;
    std::fs::remove_file(&probe)
}

/// Fails, naming `flag` and `path`, unless a file can be created at `path`: its folder exists
/// and takes a new file, and `path` is not a folder. Called before long work, so that a typo
/// costs a moment rather than a render.
pub fn check_writable(flag: &str, path: &Path) -> anyhow::Result<()> {
    let folder = folder_of(path);
    if !folder.is_dir() {
        bail!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            folder.display()
        );
    }
    if path.is_dir() {
        bail!("{flag} {}: is a folder, not a file", path.display());
    }
    probe(&folder).with_context(|| {
        format!(
            "{flag} {}: cannot create a file in {}",
            path.display(),
            folder.display()
        )
    })
}

/// Checks that the folder `dir` takes new files or, when it does not exist yet, that its
/// nearest existing parent does (the folder is created when the results are written), naming
/// `flag`.
pub fn check_writable_dir(flag: &str, dir: &Path) -> anyhow::Result<()> {
    let existing = dir
        .ancestors()
        .find(|a| !a.as_os_str().is_empty() && a.exists())
        .unwrap_or(Path::new("."));
    if !existing.is_dir() {
        bail!(
            "{flag} {}: {} is not a folder",
            dir.display(),
            existing.display()
        );
    }
    probe(existing).with_context(|| {
        format!(
            "{flag} {}: cannot create files in {}",
            dir.display(),
            existing.display()
        )
    })
}

/// Writes through a temporary file in the same folder and renames it into place
/// (`lazysolid_compute::atomic_file`), so that an interrupted or failed write leaves no half
/// file under `path`; `write`'s errors name the file.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    atomic_file::write_atomically(path, |w| {
        write(w).with_context(|| format!("writing {}", path.display()))
    })
}

/// Writes an RGB PNG whole or not at all.
pub fn write_png(path: &Path, width: u32, height: u32, rgb: &[[u8; 3]]) -> anyhow::Result<()> {
    let bytes: Vec<u8> = rgb.iter().flatten().copied().collect();
    write_atomically(path, |w| {
        Ok(image::write_buffer_with_format(
            w,
            &bytes,
            width,
            height,
            image::ExtendedColorType::Rgb8,
            image::ImageFormat::Png,
        )?)
    })
}
