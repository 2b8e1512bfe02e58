//! The OFF format (Object File Format, as written by CGAL and Geomview): an `OFF` header, a
//! line `vertices faces edges`, the vertices, then faces as `k i1 … ik` (polygons are
//! triangulated as fans). `#` starts a comment; extra values after a vertex or a face (colours)
//! are ignored.

use super::{Mesh, MeshError};
use glam::Vec3;
use std::path::Path;

/// Most vertices or faces a file may declare: indices are u32 and the counts size allocations.
const MAX_COUNT: usize = 1 << 28;

struct Lines<'a> {
    inner: std::iter::Enumerate<std::str::Lines<'a>>,
}

impl<'a> Lines<'a> {
    /// The next line with content, comments removed: `(1-based line number, tokens)`.
    fn next_tokens(&mut self) -> Option<(usize, Vec<&'a str>)> {
        for (i, line) in self.inner.by_ref() {
            let content = line.split('#').next().unwrap_or("");
            let tokens: Vec<&str> = content.split_whitespace().collect();
            if !tokens.is_empty() {
                return Some((i + 1, tokens));
            }
        }
        None
    }
}

pub(super) fn load(path: &Path) -> Result<Mesh, MeshError> {
    let text = std::fs::read_to_string(path).map_err(|source| MeshError::Io {
        file: path.to_path_buf(),
        source,
    })?;
    parse(&text, path)
}

pub(super) fn parse(text: &str, path: &Path) -> Result<Mesh, MeshError> {
    let err = |line: usize, field: &str, problem: String| MeshError::Parse {
        file: path.to_path_buf(),
        line,
        field: field.to_string(),
        problem,
    };
    let mut lines = Lines {
        inner: text.lines().enumerate(),
    };
    let (line, mut tokens) = lines
        .next_tokens()
        .ok_or_else(|| err(0, "header", "the file is empty".into()))?;
    let header = tokens[0];
    if !header.ends_with("OFF") {
        return Err(err(
            line,
            "header",
            format!("expected OFF, found {header:?}"),
        ));
    }
    if header != "OFF" && header != "COFF" && header != "NOFF" && header != "CNOFF" {
        return Err(err(
            line,
            "header",
            format!("unsupported OFF variant {header:?} (OFF, COFF, NOFF and CNOFF are read)"),
        ));
    }
    let mut count_line = line;
    if tokens.len() > 1 {
        tokens.remove(0);
    } else {
        (count_line, tokens) = lines.next_tokens().ok_or_else(|| {
            err(
                0,
                "counts",
                "missing the line `vertices faces edges`".into(),
            )
        })?;
    }
    let count = |i: usize, name: &str| -> Result<usize, MeshError> {
        let t = tokens
            .get(i)
            .ok_or_else(|| err(count_line, name, "missing".into()))?;
        let v: usize = t
            .parse()
            .map_err(|_| err(count_line, name, format!("{t:?} is not a count")))?;
        if v > MAX_COUNT {
            return Err(err(
                count_line,
                name,
                format!("{v} exceeds the limit of {MAX_COUNT}"),
            ));
        }
        Ok(v)
    };
    let vertex_count = count(0, "vertex count")?;
    let face_count = count(1, "face count")?;

    let mut positions = Vec::with_capacity(vertex_count);
    for v in 0..vertex_count {
        let (line, tokens) = lines.next_tokens().ok_or_else(|| {
            err(
                0,
                &format!("vertex {v}"),
                format!("the file ends after {v} of {vertex_count} vertices"),
            )
        })?;
        let mut xyz = [0f32; 3];
        for (c, axis) in ["x", "y", "z"].iter().enumerate() {
            let field = format!("vertex {v} coordinate {axis}");
            let t = tokens
                .get(c)
                .ok_or_else(|| err(line, &field, "missing".into()))?;
            xyz[c] = t
                .parse()
                .map_err(|_| err(line, &field, format!("{t:?} is not a number")))?;
            if !xyz[c].is_finite() {
                return Err(err(line, &field, format!("{t:?} is not finite")));
            }
        }
        positions.push(Vec3::from_array(xyz));
    }

    let mut triangles = Vec::with_capacity(face_count);
    for f in 0..face_count {
        let (line, tokens) = lines.next_tokens().ok_or_else(|| {
            err(
                0,
                &format!("face {f}"),
                format!("the file ends after {f} of {face_count} faces"),
            )
        })?;
        let field = format!("face {f}");
        let k: usize = tokens[0].parse().map_err(|_| {
            err(
                line,
                &field,
                format!("vertex count {:?} is not a count", tokens[0]),
            )
        })?;
        if k < 3 {
            return Err(err(
                line,
                &field,
                format!("a face needs at least 3 vertices, found {k}"),
            ));
        }
        if tokens.len() < k + 1 {
            return Err(err(
                line,
                &field,
                format!("declares {k} vertices but lists {}", tokens.len() - 1),
            ));
        }
        let mut indices = Vec::with_capacity(k);
        for (j, t) in tokens[1..=k].iter().enumerate() {
            let i: u32 = t.parse().map_err(|_| {
                err(
                    line,
                    &format!("face {f} index {j}"),
                    format!("{t:?} is not a vertex index"),
                )
            })?;
            if i as usize >= vertex_count {
                return Err(err(
                    line,
                    &format!("face {f} index {j}"),
                    format!("vertex {i} does not exist (the file has {vertex_count} vertices)"),
                ));
            }
            indices.push(i);
        }
        for j in 1..k - 1 {
            triangles.push([indices[0], indices[j], indices[j + 1]]);
        }
    }
    Ok(Mesh {
        positions,
        triangles,
        uvs: None,
        source: path.to_path_buf(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(s: &str) -> Result<Mesh, MeshError> {
        parse(s, Path::new("test.off"))
    }

    #[test]
    fn reads_a_quad_as_two_triangles_with_comments_and_colours() {
        let m = parse_str(
            "OFF # header\n# a comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n",
        )
        .unwrap();
        assert_eq!(m.positions.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn counts_on_the_header_line() {
        let m = parse_str("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(m.triangles.len(), 1);
    }

    #[test]
    fn errors_name_line_and_field() {
        let cases = [
            ("PLY\n", "test.off:1: header"),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n",
                "vertex 2: the file ends after 2 of 3 vertices",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 zz 0\n0 1 0\n3 0 1 2\n",
                "test.off:4: vertex 1 coordinate y: \"zz\" is not a number",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
                "test.off:6: face 0 index 2: vertex 7 does not exist",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
                "face 0: a face needs at least 3 vertices",
            ),
            (
                "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n",
                "vertex 2 coordinate z: \"nan\" is not finite",
            ),
            (
                "OFF\n999999999999 1 0\n",
                "vertex count: 999999999999 exceeds the limit",
            ),
            ("", "header: the file is empty"),
        ];
        for (text, expected) in cases {
            let e = parse_str(text).unwrap_err().to_string();
            assert!(e.contains(expected), "{text:?}: {e}");
        }
    }
}
