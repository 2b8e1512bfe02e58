//! Writing a file under a temporary name in the same folder, then renaming it into place.
//!
//! A rename within one folder is atomic on the file systems we run on, so readers (a viewer, a
//! test comparing against a reference, a second render) see either the old file or the complete
//! new one, never a truncated image.

use super::OutputError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The temporary name: hidden, in the destination folder, unique per process and per write so
/// that two threads writing the same image do not share a temporary file.
fn partial_path(path: &Path) -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let serial = NEXT.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.partial-{}-{serial}", std::process::id()))
}

fn io_error(file: &Path, action: impl Into<String>, cause: std::io::Error) -> OutputError {
    OutputError::Io {
        file: file.to_path_buf(),
        action: action.into(),
        cause,
    }
}

/// Runs `write` on a buffered temporary file next to `path` and renames it to `path` on
/// success; on any failure the temporary file is removed and `path` is left as it was.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), OutputError>,
) -> Result<(), OutputError> {
    if path.file_name().is_none() {
        return Err(io_error(
            path,
            "write an image",
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the path has no file name",
            ),
        ));
    }
    let tmp = partial_path(path);
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.display().to_string(),
        _ => ".".to_string(),
    };
    let file = File::create(&tmp)
        .map_err(|e| io_error(path, format!("create a temporary file in {folder}"), e))?;
    let result = write_then_rename(path, &tmp, BufWriter::new(file), write);
    if result.is_err() {
        // Best effort: the error being returned matters more than a failed clean-up.
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn write_then_rename(
    path: &Path,
    tmp: &Path,
    mut writer: BufWriter<File>,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), OutputError>,
) -> Result<(), OutputError> {
    write(&mut writer)?;
    writer.flush().map_err(|e| io_error(path, "write", e))?;
    // Closed before the rename so no handle to the temporary name outlives it.
    drop(writer);
    std::fs::rename(tmp, path)
        .map_err(|e| io_error(path, format!("rename {} into place", tmp.display()), e))
}
