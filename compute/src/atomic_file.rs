//! Writing a file under a temporary name in its own folder, then renaming it into place: the
//! one writer every output of the workspace goes through (images, volumes, tables, cache
//! entries, meshes).
//!
//! A rename within one folder is atomic on the file systems we run on, so a reader (a viewer,
//! a test comparing against a reference, a second process reading the cache) sees either the
//! old file or the complete new one, and a failed or interrupted write leaves no half file
//! under the destination's name. The temporary file is hidden (`.NAME.…partial`), unique per
//! write (two threads writing one path never share it) and removed when the write fails.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// What failed while writing `path`: the step and the operating system's reason. The reason
/// is part of the message and not a `source()`, so that chain printers (`anyhow`'s `{:#}`)
/// do not repeat it.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot {action}: {cause}", path.display())]
pub struct AtomicWriteError {
    /// The destination.
    pub path: PathBuf,
    /// The step that failed, in words ("create a temporary file in out/", "rename … into
    /// place").
    pub action: String,
    /// The operating system's error.
    pub cause: std::io::Error,
}

/// Runs `write` on a buffered temporary file next to `path` and renames it to `path` once
/// `write` succeeded and the buffer is flushed; on any failure `path` is left as it was and
/// the temporary file is removed. `E` is the caller's error type: `write`'s own errors pass
/// through unchanged, the writer's become an [`AtomicWriteError`].
pub fn write_atomically<E: From<AtomicWriteError>>(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), E>,
) -> Result<(), E> {
    let fail = |action: String, cause| AtomicWriteError {
        path: path.to_path_buf(),
        action,
        cause,
    };
    let Some(name) = path.file_name() else {
        return Err(fail(
            "write a file".into(),
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the path has no file name",
            ),
        )
        .into());
    };
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".{}.", name.to_string_lossy()))
        .suffix(".partial")
        .tempfile_in(folder)
        .map_err(|e| {
            fail(
                format!("create a temporary file in {}", folder.display()),
                e,
            )
        })?;
    // Dropping the temporary file on an early return removes it.
    let (file, tmp_path) = tmp.into_parts();
    let mut writer = BufWriter::new(file);
    write(&mut writer)?;
    writer
        .flush()
        .map_err(|e| fail("write the temporary file".into(), e))?;
    // Closed before the rename so no handle to the temporary name outlives it.
    drop(writer);
    tmp_path
        .persist(path)
        .map_err(|e| fail(format!("rename {} into place", e.path.display()), e.error).into())
}

/// [`write_atomically`] of bytes already in memory.
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> Result<(), AtomicWriteError> {
    write_atomically(path, |w| {
        w.write_all(bytes).map_err(|e| AtomicWriteError {
            path: path.to_path_buf(),
            action: "write the temporary file".into(),
            cause: e,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_write_lands_whole_and_a_failed_one_leaves_the_old_file_alone() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.bin");
        write_bytes_atomically(&path, b"first").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        #[derive(Debug)]
        struct Failed;
        impl From<AtomicWriteError> for Failed {
            fn from(_: AtomicWriteError) -> Failed {
                Failed
            }
        }
        let r: Result<(), Failed> = write_atomically(&path, |w| {
            w.write_all(b"half").unwrap();
            Err(Failed)
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        assert_eq!(names(dir.path()), ["out.bin"], "no temporary file left");
        let missing = dir.path().join("no-such-folder").join("x.bin");
        let e = write_bytes_atomically(&missing, b"x").unwrap_err();
        assert!(e.to_string().contains("no-such-folder"), "{e}");
    }
}
