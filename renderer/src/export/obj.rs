//! A piece as OBJ with its atlas: positions in the rest pose's world coordinates (OBJ has no
//! transforms), texture coordinates with OBJ's v up, the outer surface and the cap faces in
//! their own groups, and a material library whose `map_Kd` is the piece's PNG.

use super::atlas::PieceAtlas;
use crate::output::{write_atomically, OutputError};
use glam::Affine3A;
use std::io::Write;
use std::path::Path;

/// Writes `dir/<stem>.obj` and `dir/<stem>.mtl` (the PNG, `dir/<stem>.png`, is written by the
/// caller), each through a temporary name.
pub(crate) fn write_obj(
    dir: &Path,
    stem: &str,
    atlas: &PieceAtlas,
    rest: Affine3A,
) -> Result<(), OutputError> {
    let obj = dir.join(format!("{stem}.obj"));
    write_atomically::<OutputError>(&obj, |w| {
        let io = |cause| OutputError::Io {
            file: obj.clone(),
            action: "write".into(),
            cause,
        };
        writeln!(
            w,
            "# lazysolid piece with its matter: {} vertices, {} triangles\nmtllib {stem}.mtl\no {stem}",
            atlas.positions.len(),
            atlas.triangles.len()
        )
        .map_err(io)?;
        for p in &atlas.positions {
            let p = rest.transform_point3(*p);
            writeln!(w, "v {} {} {}", p.x, p.y, p.z).map_err(io)?;
        }
        for uv in &atlas.uvs {
            writeln!(w, "vt {} {}", uv.x, 1.0 - uv.y).map_err(io)?;
        }
        writeln!(w, "usemtl {stem}").map_err(io)?;
        for (group, interior) in [("surface", false), ("interior", true)] {
            let mut faces = atlas
                .triangles
                .iter()
                .zip(&atlas.interior)
                .filter(|(_, &f)| f == interior)
                .peekable();
            if faces.peek().is_none() {
                continue;
            }
            writeln!(w, "g {group}").map_err(io)?;
            for ([a, b, c], _) in faces {
                let (a, b, c) = (a + 1, b + 1, c + 1);
                writeln!(w, "f {a}/{a} {b}/{b} {c}/{c}").map_err(io)?;
            }
        }
        Ok(())
    })?;
    let mtl = dir.join(format!("{stem}.mtl"));
    write_atomically::<OutputError>(&mtl, |w| {
        write!(
            w,
            "# lazysolid: the piece's matter, baked from its solid texture\n\
             newmtl {stem}\nKd 1 1 1\nKs 0 0 0\nillum 1\nmap_Kd {stem}.png\n"
        )
        .map_err(|cause| OutputError::Io {
            file: mtl.clone(),
            action: "write".into(),
            cause,
        })
    })
}
