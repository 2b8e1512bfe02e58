//! Fragments as Wavefront OBJ for other tools: the original surface and the cap faces in their
//! own groups and materials (`surface`, `interior`), so a DCC tool or game engine can give the
//! interior its own look. Written through a temporary file, so a failure leaves no partial OBJ.

use super::Fragment;
use crate::output::{write_atomically, OutputError};
use std::io::Write;
use std::path::Path;

/// Writes `fragment` to `path` as object `name`, referring to the material library `mtllib`
/// (a file name next to it) when given.
///
/// # Errors
/// The file cannot be created, written or renamed into place.
pub fn write_fragment_obj(
    fragment: &Fragment,
    path: &Path,
    name: &str,
    mtllib: Option<&str>,
) -> Result<(), OutputError> {
    write_atomically(path, |w| {
        let io = |cause| OutputError::Io {
            file: path.to_path_buf(),
            action: "write".into(),
            cause,
        };
        let caps = fragment.interior.iter().filter(|&&f| f).count();
        writeln!(
            w,
            "# lazysolid fragment: {} vertices, {} triangles ({caps} interior)",
            fragment.positions.len(),
            fragment.triangles.len()
        )
        .map_err(io)?;
        if let Some(lib) = mtllib {
            writeln!(w, "mtllib {lib}").map_err(io)?;
        }
        writeln!(w, "o {name}").map_err(io)?;
        for p in &fragment.positions {
            writeln!(w, "v {} {} {}", p.x, p.y, p.z).map_err(io)?;
        }
        for (group, interior) in [("surface", false), ("interior", true)] {
            let mut faces = fragment.triangles_of(interior).peekable();
            if faces.peek().is_none() {
                continue;
            }
            writeln!(w, "g {group}\nusemtl {group}").map_err(io)?;
            for [a, b, c] in faces {
                writeln!(w, "f {} {} {}", a + 1, b + 1, c + 1).map_err(io)?;
            }
        }
        Ok(())
    })
}

/// Writes the material library the fragments refer to: `surface` and `interior`, plain diffuse
/// colours a tool can replace.
///
/// # Errors
/// As [`write_fragment_obj`].
pub fn write_material_library(path: &Path) -> Result<(), OutputError> {
    write_atomically(path, |w| {
        w.write_all(
            b"# lazysolid fragments: the original surface and the faces the cuts made\n\
              newmtl surface\nKd 0.8 0.8 0.8\n\nnewmtl interior\nKd 0.8 0.45 0.3\n",
        )
        .map_err(|cause| OutputError::Io {
            file: path.to_path_buf(),
            action: "write".into(),
            cause,
        })
    })
}
